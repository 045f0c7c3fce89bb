#!/usr/bin/env bash
# The main job: set up, build, then build the default scene's LOD DAG and check it.
# (The default scene is the shipped cage, assets/horned_cube.obj, subdivided 4 times: 175k triangles.)
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
mkdir -p out
build/vgeo build assets/horned_cube.obj --subdiv 4 -o out/horned_cube.vgeo --stats out/horned_cube.build.json
build/vgeo check out/horned_cube.vgeo --cuts 32

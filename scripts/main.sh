#!/usr/bin/env bash
# The main job: set up, build, build the default asset's LOD DAG, check it, and render the default
# scene (a 32 x 32 grid of it: 179 million virtual triangles) with lavapipe to out/default.png.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
mkdir -p out
build/vgeo build assets/horned_cube.obj --subdiv 4 -o out/horned_cube.vgeo --stats out/horned_cube.build.json
build/vgeo check out/horned_cube.vgeo --cuts 32
build/vgeo render out/horned_cube.vgeo --grid 32 --size 1280x720 -o out/default.png --compare-cpu --stats out/default.render.json
cat out/default.render.json

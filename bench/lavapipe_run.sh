#!/usr/bin/env bash
# The lavapipe / CPU benchmarks of bench/README.md, on this machine: `vgeo bench build` (shipped cage and
# CGAL's armadillo and bunny00, --subdiv 0..3, 1 and 2 threads) and `vgeo bench frame` (the main job's
# default scene at 1280x720 and 1920x1080). Writes bench/results/build-<date>/ and frame-lavapipe-<date>/,
# or, when that folder holds a run already, the same name with the commit appended (a re-run the same day
# once overwrote the results bench/README.md quotes).
# Usage: bash bench/lavapipe_run.sh [build|frame]...   (both when none is named)
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh > /dev/null
V=build/vgeo
day=$(date +%F)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
tar xzf /usr/share/doc/libcgal-dev/data.tar.gz -C "$work" data/meshes/armadillo.off data/meshes/bunny00.off
for what in ${@:-build frame}; do
  out=bench/results/$what-lavapipe-$day
  [ "$what" = build ] && out=bench/results/build-$day  # CPU only
  [ -e "$out" ] && out=$out-$(git rev-parse --short HEAD 2>/dev/null || date +%H%M%S)
  mkdir -p "$out"
  case $what in
    build)
      $V bench build assets/horned_cube.obj "$work/data/meshes/armadillo.off" "$work/data/meshes/bunny00.off" \
        --subdiv 0,1,2,3 --threads 1,2 --repeat 3 -o "$out/build.json" ;;
    frame)
      $V build assets/horned_cube.obj --subdiv 4 -o "$work/horned_cube.vgeo" -q > /dev/null
      $V bench frame "$work/horned_cube.vgeo" --grids 32,316 --sizes 1280x720,1920x1080 --cameras corner,inside,surface --frames 5 \
        -o "$out/frame.json" ;;
    *) echo "unknown benchmark '$what' (build or frame)" >&2; exit 1 ;;
  esac
done

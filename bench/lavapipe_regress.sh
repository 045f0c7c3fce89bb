#!/usr/bin/env bash
# lavapipe_regress.sh: the headline lavapipe numbers of the working tree against a baseline build, both
# run here in the same call, alternating (this machine's speed drifts; only ratios within one run mean
# anything). Run it before resolving work that touches the builder, the file layout, the shaders or the
# renderer.
#   bash bench/lavapipe_regress.sh [BASE_COMMIT]     (default: the commit in bench/lavapipe_baseline.txt)
# The base is built in build-base/ from a worktree of BASE_COMMIT (a few minutes the first time). The set,
# small enough for 2 cores (~5 minutes a round): `bench cut` of the shipped cage --subdiv 2 at 1, 100 and
# 1,000 instances (persistent, occlusion off); `bench frame` of the default scene (cage --subdiv 4, 32 x 32)
# at 1280x720, corner and inside, occlusion auto and off; the cow close-up with patches. ROUNDS (default 2)
# alternations; the minimum of the rounds is compared (bench/regress.py, more than 10% slower flagged).
# Writes out/lavapipe-regress/{base,new}.json and verdict.txt.
set -euo pipefail
cd "$(dirname "$0")/.."
base_commit=${1:-$(cat bench/lavapipe_baseline.txt)}
ROUNDS=${ROUNDS:-2}
bash scripts/build.sh > /dev/null
if [ "$(git -C build-base/src rev-parse HEAD 2>/dev/null)" != "$(git rev-parse "$base_commit^{commit}")" ]; then
  rm -rf build-base && git worktree prune
  git worktree add -f --detach build-base/src "$base_commit" > /dev/null 2>&1
  cmake -S build-base/src -B build-base/build -DCMAKE_BUILD_TYPE=Release > /dev/null
fi
cmake --build build-base/build -j "$(nproc)" --target vgeo > /dev/null
out=out/lavapipe-regress
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
rm -rf "$out" && mkdir -p "$out"
tar xzf /usr/share/doc/libcgal-dev/data.tar.gz -C "$work" data/meshes/cow.off

run_set() {  # binary, folder
  local bin=$1 dir=$2 f=$work/$(basename $2 | cut -d- -f1)
  mkdir -p "$dir" "$f"
  [ -f "$f/hc2.vgeo" ] || {
    $bin build assets/horned_cube.obj --subdiv 2 -o "$f/hc2.vgeo" -q
    $bin build assets/horned_cube.obj --subdiv 4 -o "$f/hc4.vgeo" -q
    $bin build "$work/data/meshes/cow.off" --subdiv 1 -o "$f/cow1.vgeo" -q
  } > /dev/null
  local occ=(--occlusion off)  # builds from before the option measured the cut alone on lavapipe anyway
  $bin bench cut --help | grep -q -- --occlusion || occ=()
  $bin bench cut "$f/hc2.vgeo" -o "$dir/cut.json" --sizes 1,100,1000 --layouts grid --taus 1 --traversals persistent \
    "${occ[@]}" --frames 3 --size 1280x720 2> /dev/null
  $bin bench frame "$f/hc4.vgeo" -o "$dir/frame_default.json" --grids 32 --sizes 1280x720 --cameras corner,inside \
    --rasters auto --occlusion auto,off --frames 3 2> /dev/null
  $bin render "$f/cow1.vgeo" --camera 0.2,0.2,0.4,0,0,0 --tau 0.5 --size 1280x720 --frames 4 -o "$work/cow.png" \
    --stats "$dir/cow.json" > /dev/null 2>&1
}
for r in $(seq 1 "$ROUNDS"); do
  run_set build-base/build/vgeo "$work/base-$r"
  run_set build/vgeo "$work/new-$r"
done
for who in base new; do
  for r in $(seq 1 "$ROUNDS"); do python3 bench/regress.py merge "$work/$who-$r" -o "$work/$who-$r.json" > /dev/null; done
  python3 bench/regress.py minimum "$out/$who.json" "$work/$who"-*.json
done
python3 bench/regress.py compare "$out/base.json" "$out/new.json" | tee "$out/verdict.txt"

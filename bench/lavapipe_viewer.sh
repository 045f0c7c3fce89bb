#!/usr/bin/env bash
# The viewer's own cost on lavapipe (bench/viewer.md): the default scene at 1280x720 from
# its default camera, `vgeo view --no-vsync` under Xvfb for 65 frames (the panel shown, and hidden with
# Tab) against `vgeo render --frames 65`, both timing the frames after the fifth; three rounds in
# alternating order. Prints a line a run and writes bench/results/viewer-lavapipe-<date>/runs.txt.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh > /dev/null
V=$PWD/build/vgeo
export VK_DRIVER_FILES=$(ls /usr/share/vulkan/icd.d/lvp_icd*.json | head -1)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
out=bench/results/viewer-lavapipe-$(date +%F)
mkdir -p "$out"
$V build assets/horned_cube.obj --subdiv 4 -o "$work/hc.vgeo" -q > /dev/null
printf '65 quit\n' > "$work/panel.txt"
printf '0 key Tab\n65 quit\n' > "$work/hidden.txt"
render() {
  $V render "$work/hc.vgeo" --grid 32 --size 1280x720 --frames 65 -o "$work/r.png" --stats "$work/r.json" > /dev/null
  python3 -c "import json; print('render: %.2f ms a frame' % json.load(open('$work/r.json'))['frame_mean_ms'])"
}
view() {
  echo -n "view, $1: "
  xvfb-run -a -s '-screen 0 1920x1080x24' $V view "$work/hc.vgeo" --grid 32 --size 1280x720 --no-vsync \
    --script "$work/$1.txt" | tail -1
}
{
  echo "# $(git rev-parse --short HEAD) $(date -u +%FT%TZ) $($V --version)"
  for round in 1 2 3; do
    if [ $((round % 2)) = 1 ]; then render; view panel; view hidden; else view hidden; view panel; render; fi
  done
} | tee "$out/runs.txt"

#!/usr/bin/env bash
# GPU renderer benchmark on an NVIDIA machine without the project's packages: 10,000 and 100,000 instances
# of armadillo --subdiv 2 (1.25M triangles) at 1920x1080, tau 1, each traversal; a validation run.
# Expects, beside the checkout: .gl/ (Vulkan loader debs), .dev/vgeo (the binary built here), .dev/lib/
# (libtinygltf, libstb from `ldd build/vgeo`), .dev/data/armadillo.off, and the
# vulkan-validationlayers .deb in .dev/. Writes JSON to $OUT.
set -uo pipefail
source bench/gpu_env.sh
$V build .dev/data/armadillo.off --subdiv 2 -o /tmp/arm2.vgeo --stats $OUT/build.json --threads 16 -q
validated $V render /tmp/arm2.vgeo --grid 10 --size 640x480 --validate --compare-cpu -o /tmp/val.png --stats $OUT/validate.json 2>&1 | tail -5
for t in persistent levels flat; do
  extra=""; [ $t = persistent ] && extra="--compare-cpu"
  $V render /tmp/arm2.vgeo --grid 100 --size 1920x1080 --traversal $t --frames 30 $extra -o /tmp/grid_$t.png --stats $OUT/h100_$t.json 2>&1 | tail -3
done
for t in persistent levels; do
  $V render /tmp/arm2.vgeo --grid 316 --size 1920x1080 --traversal $t --frames 30 -o /tmp/g316_$t.png --stats $OUT/h100_100k_$t.json 2>&1 | tail -2
done

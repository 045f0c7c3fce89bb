#!/usr/bin/env bash
# vgeo bench frame on an NVIDIA machine (see bench/gpu_run.sh for what .gl/ and .dev/ must hold): the main
# job's default scene (shipped cage --subdiv 4, 32 x 32) and the largest cut scene (armadillo --subdiv 2,
# 316 x 316 = 99,856 instances) at 1280x720 and 1920x1080, with the surface close-up (leaves as patches);
# and the default scene, a patch close-up and an open triangle mesh after one round (every face a tree
# patch, boundaries) under validation.
set -uo pipefail
source bench/gpu_env.sh
$V build assets/horned_cube.obj --subdiv 4 -o /tmp/hc.vgeo -q > /dev/null
$V build .dev/data/armadillo.off --subdiv 2 -o /tmp/arm2.vgeo --threads 16 -q > /dev/null
validated $V render /tmp/hc.vgeo --grid 32 --size 1280x720 --validate --compare-cpu -o $OUT/default.png --stats $OUT/validate_default.json 2>&1 | tail -3
$V build assets/horned_cube.obj --subdiv 2 -o /tmp/hc2.vgeo -q > /dev/null
for mode in lit patch; do
  validated $V render /tmp/hc2.vgeo --size 1280x720 --camera 1.2,1.0,2.2,0,0,0.5 --mode $mode --validate --compare-cpu -o $OUT/patches_$mode.png \
    --stats $OUT/validate_patches_$mode.json 2>&1 | tail -3
done
$V build .dev/data/corner_tris_with_hole.off --subdiv 1 -o /tmp/ct1.vgeo -q > /dev/null
for mode in lit patch; do
  validated $V render /tmp/ct1.vgeo --size 1280x720 --mode $mode --validate --compare-cpu -o $OUT/trees_$mode.png --stats $OUT/validate_trees_$mode.json 2>&1 | tail -3
done
$V bench frame /tmp/hc.vgeo --grids 32 --sizes 1280x720,1920x1080 --cameras corner,inside,surface --frames 20 -o $OUT/frame_default.json 2>&1 | tail -8
$V bench frame /tmp/arm2.vgeo --grids 100,316 --sizes 1280x720,1920x1080 --cameras corner,inside --frames 20 -o $OUT/frame_largest.json 2>&1 | tail -16

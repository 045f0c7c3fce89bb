#!/usr/bin/env bash
# Occlusion culling on an NVIDIA machine (see bench/gpu_run.sh for what .gl/ and .dev/ must hold): the
# dense forest (99,856 instances of armadillo --subdiv 2) from the ground, from above and along the
# fly-through, with occlusion culling auto, on and off, twice in alternating order; the default scene and
# the 99,856 grid the three ways (and with .dev/vgeo_base, a binary of an earlier commit, when there is one);
# then the forest's ground and above views under validation with the CPU cut compared, and their pictures
# with and without occlusion compared byte for byte.
set -uo pipefail
source bench/gpu_env.sh
$V build assets/horned_cube.obj --subdiv 4 -o /tmp/hc.vgeo -q > /dev/null
$V build .dev/data/armadillo.off --subdiv 2 -o /tmp/arm2.vgeo --threads 16 -q > /dev/null
forest="/tmp/arm2.vgeo --layout forest --grids 316 --sizes 1920x1080 --cameras ground,above,flythrough --frames 20 --rasters auto"
$V bench frame $forest --occlusion auto,on,off -o $OUT/forest_1.json 2>&1 | grep -v "^ *$"
$V bench frame $forest --occlusion off,on,auto -o $OUT/forest_2.json 2>&1 | grep -v "^ *$"
for bin in $V .dev/vgeo_base; do
  [ -x $bin ] || continue
  occ="--occlusion auto,on,off"; tag=""
  [ $bin = $V ] || { occ=""; tag=_base; }
  $bin bench frame /tmp/hc.vgeo --grids 32 --sizes 1920x1080 --cameras corner,inside --frames 20 --rasters auto $occ \
    -o $OUT/default$tag.json 2>&1 | grep -v "^ *$"
  $bin bench frame /tmp/arm2.vgeo --grids 316 --sizes 1920x1080 --cameras corner,inside --frames 20 --rasters auto $occ \
    -o $OUT/largest$tag.json 2>&1 | grep -v "^ *$"
done
for cam in ground above; do
  pose=$(grep -B3 "\"camera\": \"$cam\"" $OUT/forest_1.json | grep -m1 -o '"camera_option": "[^"]*"' | cut -d'"' -f4)
  echo "$cam: --camera $pose"
  for occ in on off; do
    flag="--occlusion $occ"
    validated $V render /tmp/arm2.vgeo --layout forest --grid 316 \
      --size 1920x1080 --camera "$pose" $flag --validate --compare-cpu -o /tmp/${cam}_$occ.png \
      --stats /tmp/validate_${cam}_$occ.json 2>&1 | tail -2
    echo "exit $?"
  done
  cmp /tmp/${cam}_on.png /tmp/${cam}_off.png && echo "$cam: pictures equal with and without occlusion"
done
# One instance (culled by the traversal's workers) and the default scene (64 lanes an instance).
for grid in 1 32; do
  validated $V render /tmp/hc.vgeo --grid $grid --size 1920x1080 \
    --validate --compare-cpu -o /tmp/hc_$grid.png 2>&1 | tail -2
  echo "exit $?"
done
cp /tmp/ground_on.png $OUT/forest_ground.png

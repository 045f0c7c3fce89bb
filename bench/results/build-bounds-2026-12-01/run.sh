#!/bin/bash
# vgeo_head (6b24634) against vgeo_new (the clusters' bounds found in the rounds' waits) by
# bench/device_build_ab.sh, then the rounds one by one. Run from the repository root with .dev/ as
# bench/device_build_runs.sh describes, plus .dev/vgeo_tr; results under $OUT.
set -u
bash bench/device_build_ab.sh
. bench/device_build_runs.sh  # D, W
# The rounds one by one (vgeo_tr: vgeo_new printing each round's stages), Loop x2 on 1 and 16 threads.
for t in 1 16 16 16; do
  rm -f $W/o.vgeo; $D/vgeo_tr build $W/a2.obj -o $W/o.vgeo --threads $t --stats $W/s.json 2>&1 >/dev/null | grep TR > $W/tr.txt
  { echo "== $t threads"; cat $W/tr.txt; } >> $OUT/rounds.txt
done

#!/bin/bash
# As run.sh with pieces from 256 KB on (vgeo_new): armadillo's cage (1.6 MB) at --subdiv 1, 2 and 3
# on 16 threads, Loop x2 as OFF on 2 and 16, four rounds, the order alternating.
set -u
. bench/device_build_runs.sh  # D, W, host.txt and run()
A=$D/data/armadillo.off
$D/peers/prep $A $W/a2.bin 2 loop >/dev/null && $D/peers/bin2obj $W/a2.bin $W/a2.obj >/dev/null
bash bench/results/build-off-2026-12-01/obj2off.sh $W/a2.obj $W/a2.off
for r in 1 2 3 4; do
  if [ $((r % 2)) = 1 ]; then bins="vgeo_head vgeo_new"; else bins="vgeo_new vgeo_head"; fi
  for b in $bins; do
    for s in 1 2 3; do run $b $A $s 16 $r cage; done
    for t in 2 16; do run $b $W/a2.off 0 $t $r a2off; done
  done
done
grep -c . $OUT/runs.jsonl; date -u >> $OUT/host.txt

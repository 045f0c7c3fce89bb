#!/bin/bash
# The OFF reader in pieces on the threads (vgeo_new) against the one-thread reader (vgeo_head,
# 6e90355): armadillo Loop x2 written as OFF (32 MB) on 1, 2, 4, 8 and 16 threads, and armadillo's
# cage (1.6 MB, under the size read in pieces) at --subdiv 2 on 16, four rounds, the order alternating;
# the load's seconds and the whole build's. Setup as results/build-2026-12-01/run.sh.
set -u
. bench/device_build_runs.sh  # D, W, host.txt and run()
A=$D/data/armadillo.off
$D/peers/prep $A $W/a2.bin 2 loop >/dev/null && $D/peers/bin2obj $W/a2.bin $W/a2.obj >/dev/null
bash bench/results/build-off-2026-12-01/obj2off.sh $W/a2.obj $W/a2.off
ls -la $W/a2.off >> $OUT/host.txt
for r in 1 2 3 4; do
  if [ $((r % 2)) = 1 ]; then bins="vgeo_head vgeo_new"; else bins="vgeo_new vgeo_head"; fi
  for b in $bins; do
    for t in 1 2 4 8 16; do run $b $W/a2.off 0 $t $r a2off; done
    run $b $A 2 16 $r cage
  done
done
grep -c . $OUT/runs.jsonl; date -u >> $OUT/host.txt

#!/bin/bash
# The shared round's trees in batches of 1, 2 and 8 blocks (vgeo_b1, vgeo_b2, vgeo_b8) against af183b8
# (vgeo_head): armadillo --subdiv 1 on 16 threads (six rounds) and 2 (three), the order turning by
# round; output bytes compared. Setup as run.sh.
set -u
. bench/device_build_runs.sh  # D, W, host.txt and run()
A=$D/data/armadillo.off
all="vgeo_head vgeo_b1 vgeo_b2 vgeo_b8"
for r in 1 2 3 4 5 6; do
  set -- $all $all; shift $((r % 4)); list=$(echo $* | cut -d' ' -f1-4)
  for b in $list; do run $b $A 1 16 $r cage; [ $r -le 3 ] && run $b $A 1 2 $r cage; done
done
grep -c . $OUT/runs.jsonl; date -u >> $OUT/host.txt

#!/bin/bash
# A triangle cage's trees from one round of the whole mesh (vgeo_new) against a round of each face's
# own neighbourhood (vgeo_head): armadillo --subdiv 1 on 16 threads and one, --subdiv 2 on 16, four
# rounds, the binaries' order alternating; output bytes compared. Setup as run.sh.
set -u
. bench/device_build_runs.sh  # D, W, host.txt and run()
A=$D/data/armadillo.off
order() { [ $(($1 % 2)) = 1 ] && echo "vgeo_head vgeo_new" || echo "vgeo_new vgeo_head"; }
for r in 1 2 3 4; do
  for b in $(order $r) $(order $((r + 1))); do run $b $A 1 16 $r cage; done
  for b in $(order $r); do run $b $A 1 1 $r cage; run $b $A 2 16 $r cage; done
done
grep -c . $OUT/runs.jsonl; date -u >> $OUT/host.txt

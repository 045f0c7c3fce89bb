#!/bin/bash
# The cage path (armadillo --subdiv 1/2/3) and Loop x2 (pre-subdivided): vgeo_head against vgeo_new,
# alternating, output bytes compared. Run from the repository root with the binaries, their libraries,
# the peers' prep/bin2obj and armadillo.off under .dev/; results under $OUT.
set -u
. bench/device_build_runs.sh  # D, W, host.txt and run()
A=$D/data/armadillo.off
for r in 1 2 3; do for s in 1 2 3; do for b in vgeo_head vgeo_new; do run $b $A $s 16 $r cage; done; done; done
for r in 1 2; do for s in 1 2; do for b in vgeo_head vgeo_new; do run $b $A $s 1 $r cage; done; done; done
echo "cage done $(date -u)" >> $OUT/host.txt
$D/peers/prep $A $W/a2.bin 2 loop >/dev/null && $D/peers/bin2obj $W/a2.bin $W/a2.obj >/dev/null
for r in 1 2 3; do for b in vgeo_head vgeo_new; do run $b $W/a2.obj 0 16 $r a2; run $b $W/a2.obj 0 1 $r a2; done; done
grep -c . $OUT/runs.jsonl; date -u >> $OUT/host.txt

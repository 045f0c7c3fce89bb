#!/bin/bash
# vgeo_head against vgeo_new on one device host: armadillo Loop x2 (eight rounds) and x3 (three) on one
# thread and 16, the two binaries' order alternating by round, with clusterlod (one thread) and
# nv_cluster_lod_builder (16) in every other round; then armadillo's cage at --subdiv 3, 2, 1 on 16
# threads and --subdiv 2 on one; the host's scaling probe before and after. Output bytes of the two
# binaries compared (a DIFF line in host.txt when they differ). Run from the repository root with
# .dev/ as bench/device_build_runs.sh describes, plus .dev/scaling_probe; results under $OUT.
set -u
. bench/device_build_runs.sh  # D, W, host.txt and run()
A=$D/data/armadillo.off
$D/scaling_probe > $OUT/probe-before.txt 2>&1
for l in 2 3; do $D/peers/prep $A $W/a$l.bin $l loop >/dev/null && $D/peers/bin2obj $W/a$l.bin $W/a$l.obj >/dev/null; done
peer() { # driver mesh threads round
  sync; echo "{\"bin\":\"$1\",\"mesh\":\"$2\",\"threads\":$3,\"round\":$4,\"peer\":$($D/peers/$1 $W/$2.bin $3 1 | tail -1)}" >> $OUT/runs.jsonl
}
order() { [ $(($1 % 2)) = 1 ] && echo "vgeo_head vgeo_new" || echo "vgeo_new vgeo_head"; }
loop_rounds() { # mesh rounds
  for r in $(seq 1 $2); do
    for t in 1 16; do for b in $(order $r); do run $b $W/$1.obj 0 $t $r $1; done; done
    if [ $((r % 2)) = 1 ] || [ $2 -lt 4 ]; then peer clod_driver $1 1 $r; peer nvlod_driver $1 16 $r; fi
  done
}
loop_rounds a2 8
loop_rounds a3 3
for r in 1 2 3; do
  for s in 3 2 1; do for b in $(order $r) $(order $((r + 1))); do run $b $A $s 16 $r cage; done; done
  for b in $(order $r); do run $b $A 2 1 $r cage; done
done
$D/scaling_probe > $OUT/probe-after.txt 2>&1
grep -c . $OUT/runs.jsonl; date -u >> $OUT/host.txt

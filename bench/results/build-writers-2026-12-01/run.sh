#!/bin/bash
# vgeo_head (325d154) against vgeo_new on one device host: armadillo Loop x2 on one thread (four
# rounds) and 16 (eight), Loop x3 on one thread (two) and 16 (four), the two binaries' order
# alternating by round; clusterlod (one thread) and nv_cluster_lod_builder (16) once a mesh; the cage
# at --subdiv 2 and 3 on 16 threads (four). Output bytes compared (a DIFF line in host.txt when they differ).
# Run from the repository root with .dev/ as bench/device_build_runs.sh describes, plus
# .dev/scaling_probe; results under $OUT.
set -u
. bench/device_build_runs.sh  # D, W, host.txt and run()
A=$D/data/armadillo.off
for l in 2 3; do $D/peers/prep $A $W/a$l.bin $l loop >/dev/null && $D/peers/bin2obj $W/a$l.bin $W/a$l.obj >/dev/null; done
peer() { # driver mesh threads round
  sync; echo "{\"bin\":\"$1\",\"mesh\":\"$2\",\"threads\":$3,\"round\":$4,\"peer\":$($D/peers/$1 $W/$2.bin $3 1 | tail -1)}" >> $OUT/runs.jsonl
}
order() { [ $(($1 % 2)) = 1 ] && echo "vgeo_head vgeo_new" || echo "vgeo_new vgeo_head"; }
for r in $(seq 1 8); do
  [ $r -le 4 ] && for b in $(order $r); do run $b $W/a2.obj 0 1 $r a2; done
  for b in $(order $r); do run $b $W/a2.obj 0 16 $r a2; done
done
for r in 1 2 3 4; do
  [ $r -le 2 ] && for b in $(order $r); do run $b $W/a3.obj 0 1 $r a3; done
  for b in $(order $r); do run $b $W/a3.obj 0 16 $r a3; done
  for b in $(order $r); do run $b $A 2 16 $r cage; done
  for b in $(order $r); do run $b $A 3 16 $r cage; done
done
$D/scaling_probe > $OUT/probe.txt 2>&1
for m in a2 a3; do peer clod_driver $m 1 1; peer nvlod_driver $m 16 1; done
grep -c . $OUT/runs.jsonl; date -u >> $OUT/host.txt

#!/bin/bash
# The cage path (armadillo --subdiv 1/2/3) and Loop x2/x3 (pre-subdivided): vgeo_head against vgeo_new.
set -u
. bench/device_build_runs.sh  # D, W, host.txt and run()
peer() { sync; echo "{\"bin\":\"$1\",\"mesh\":\"$2\",\"threads\":$3,\"round\":$4,\"peer\":$($D/peers/$1 $W/$2.bin $3 1 | tail -1)}" >> $OUT/runs.jsonl; }
A=$D/data/armadillo.off
for r in 1 2 3; do for s in 1 2 3; do for b in vgeo_head vgeo_new; do run $b $A $s 16 $r cage; done; done; done
for r in 1 2; do for s in 1 2; do for b in vgeo_head vgeo_new; do run $b $A $s 1 $r cage; done; done; done
echo "cage done $(date -u)" >> $OUT/host.txt
for l in 2 3; do $D/peers/prep $A $W/a$l.bin $l loop >/dev/null && $D/peers/bin2obj $W/a$l.bin $W/a$l.obj >/dev/null; done
for r in 1 2 3 4; do
  run vgeo_new $W/a2.obj 0 1 $r a2; peer clod_driver a2 1 $r; run vgeo_new $W/a2.obj 0 16 $r a2; peer nvlod_driver a2 16 $r
  run vgeo_head $W/a2.obj 0 16 $r a2
done
for r in 1 2; do run vgeo_new $W/a3.obj 0 1 $r a3; run vgeo_new $W/a3.obj 0 16 $r a3; run vgeo_head $W/a3.obj 0 16 $r a3; done
grep -c . $OUT/runs.jsonl; date -u >> $OUT/host.txt

#!/bin/bash
# vgeo_new with glibc's dynamic mmap threshold (default) against a fixed 4 MiB one (GLIBC_TUNABLES),
# Loop x2 and x3 (pre-subdivided) and the armadillo cage at --subdiv 1/3, alternating.
set -u
D=$(pwd)/.dev; W=/tmp/w; mkdir -p $W; export LD_LIBRARY_PATH=$D/lib
{ nproc; lscpu | grep -E "Model name"; uname -r; date -u; } > $OUT/host.txt 2>&1
run() { # mode input subdiv threads round tag
  rm -f $W/o.vgeo $W/s.json; sync
  if [ $1 = fixed ]; then export GLIBC_TUNABLES=glibc.malloc.mmap_threshold=4194304; else unset GLIBC_TUNABLES; fi
  $D/vgeo_new build $2 -o $W/o.vgeo --subdiv $3 --threads $4 --stats $W/s.json > /dev/null 2>$W/err || { echo "FAIL $*"; cat $W/err; }
  unset GLIBC_TUNABLES
  echo "{\"bin\":\"$1\",\"mesh\":\"$6\",\"subdiv\":$3,\"threads\":$4,\"round\":$5,\"stats\":$(tr -d '\n' < $W/s.json)}" >> $OUT/runs.jsonl
  cmp -s $W/o.vgeo $W/ref_$6_$3.vgeo 2>/dev/null || { [ -f $W/ref_$6_$3.vgeo ] && echo "DIFF $*" >> $OUT/host.txt || cp $W/o.vgeo $W/ref_$6_$3.vgeo; }
}
A=$D/data/armadillo.off
for l in 2 3; do $D/peers/prep $A $W/a$l.bin $l loop >/dev/null && $D/peers/bin2obj $W/a$l.bin $W/a$l.obj >/dev/null; done
for r in 1 2 3 4; do for m in dynamic fixed; do
  run $m $W/a2.obj 0 16 $r a2; run $m $W/a2.obj 0 1 $r a2; run $m $A 3 16 $r cage; run $m $A 1 16 $r cage
done; done
for r in 1 2; do for m in dynamic fixed; do run $m $W/a3.obj 0 16 $r a3; run $m $W/a3.obj 0 1 $r a3; done; done
grep -c . $OUT/runs.jsonl; date -u >> $OUT/host.txt

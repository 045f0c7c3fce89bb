#!/bin/bash
# The cage path (subdivision, patches, limit, chord errors) before and after, armadillo --subdiv 2 and 3,
# one thread and 16, alternating binaries.
set -u
D=$(pwd)/.dev; W=/tmp/w; mkdir -p $W; export LD_LIBRARY_PATH=$D/lib
{ nproc; lscpu | grep "Model name"; uname -r; date -u; } > $OUT/host.txt 2>&1
run() { # bin subdiv threads round
  rm -f $W/o.vgeo $W/s.json; sync
  $D/$1 build $D/data/armadillo.off -o $W/o.vgeo --subdiv $2 --threads $3 --stats $W/s.json > /dev/null 2>$W/err || { echo "FAIL $*"; cat $W/err; }
  echo "{\"bin\":\"$1\",\"subdiv\":$2,\"threads\":$3,\"round\":$4,\"stats\":$(tr -d '\n' < $W/s.json)}" >> $OUT/runs.jsonl
  cmp -s $W/o.vgeo $W/ref_$2.vgeo 2>/dev/null || { [ -f $W/ref_$2.vgeo ] && echo "DIFF $*" >> $OUT/host.txt || cp $W/o.vgeo $W/ref_$2.vgeo; }
}
for r in 1 2 3; do for t in 16 1; do for b in vgeo_before vgeo_cage; do run $b 2 $t $r; done; done; done
for r in 1 2; do for t in 16 1; do for b in vgeo_before vgeo_cage; do run $b 3 $t $r; done; done; done
grep -c . $OUT/runs.jsonl; date -u >> $OUT/host.txt

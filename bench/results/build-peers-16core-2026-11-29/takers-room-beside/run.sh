#!/bin/bash
# Loop x2 at 16 threads: vgeo_base, vgeo_A, vgeo_new alternating.
set -u
D=$(pwd)/.dev; W=/tmp/w; mkdir -p $W; export LD_LIBRARY_PATH=$D/lib
{ nproc; lscpu | grep "Model name"; uname -r; date -u; } > $OUT/host.txt 2>&1
$D/peers/prep $D/data/armadillo.off $W/a2.bin 2 loop >/dev/null && $D/peers/bin2obj $W/a2.bin $W/a2.obj >/dev/null
run() { rm -f $W/o.vgeo $W/s.json; sync
  $D/$1 build $W/$2.obj -o $W/o.vgeo --threads $3 --stats $W/s.json > /dev/null 2>$W/err || { echo "FAIL $*"; cat $W/err; }
  echo "{\"bin\":\"$1\",\"mesh\":\"$2\",\"threads\":$3,\"round\":$4,\"stats\":$(tr -d '\n' < $W/s.json)}" >> $OUT/runs.jsonl
  cmp -s $W/o.vgeo $W/ref_$2.vgeo 2>/dev/null || { [ -f $W/ref_$2.vgeo ] && echo "DIFF $*" >> $OUT/host.txt || cp $W/o.vgeo $W/ref_$2.vgeo; }; }
for r in $(seq 1 16); do for b in vgeo_base vgeo_A vgeo_new; do run $b a2 16 $r; done; for b in vgeo_new vgeo_A vgeo_base; do run $b a2 16 $r; done; done
for r in 1 2; do for b in vgeo_base vgeo_A vgeo_new; do run $b a2 1 $r; done; done
grep -c . $OUT/runs.jsonl

#!/bin/bash
# A/B on a device host: vgeo_base against vgeo_new alternating, with the peers (clusterlod on one
# thread, nv on 16) each round.
set -u
D=$(pwd)/.dev; W=/tmp/w; mkdir -p $W; export LD_LIBRARY_PATH=$D/lib
{ nproc; lscpu | grep "Model name"; uname -r; date -u; } > $OUT/host.txt 2>&1
for l in 2 3; do $D/peers/prep $D/data/armadillo.off $W/a$l.bin $l loop >/dev/null && $D/peers/bin2obj $W/a$l.bin $W/a$l.obj >/dev/null; done
run() { # bin mesh threads round
  rm -f $W/o.vgeo $W/s.json; sync
  $D/$1 build $W/$2.obj -o $W/o.vgeo --threads $3 --stats $W/s.json > /dev/null 2>$W/err || { echo "FAIL $*"; cat $W/err; }
  echo "{\"bin\":\"$1\",\"mesh\":\"$2\",\"threads\":$3,\"round\":$4,\"stats\":$(tr -d '\n' < $W/s.json)}" >> $OUT/runs.jsonl
  cmp -s $W/o.vgeo $W/ref_$2.vgeo 2>/dev/null || { [ -f $W/ref_$2.vgeo ] && echo "DIFF $*" >> $OUT/host.txt || cp $W/o.vgeo $W/ref_$2.vgeo; }
}
peer() { # driver mesh threads round
  sync; echo "{\"bin\":\"$1\",\"mesh\":\"$2\",\"threads\":$3,\"round\":$4,\"peer\":$($D/peers/$1 $W/$2.bin $3 1 | tail -1)}" >> $OUT/runs.jsonl
}
rounds() { # mesh count
  for r in $(seq 1 $2); do
    for b in vgeo_base vgeo_new; do run $b $1 16 $r; done; peer nvlod_driver $1 16 $r
    for b in vgeo_new vgeo_base; do run $b $1 16 $r; done
    for b in vgeo_base vgeo_new; do run $b $1 1 $r; done; peer clod_driver $1 1 $r
  done
}
rounds a2 5; rounds a3 2
grep -c . $OUT/runs.jsonl

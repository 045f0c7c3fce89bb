#!/bin/bash
# METIS (env unset) vs merge grouping (VGEO_MERGE=1 VGEO_MS=9) in one binary, alternating, with peers.
set -u
D=$(pwd)/.dev; W=/tmp/w; mkdir -p $W; export LD_LIBRARY_PATH=$D/lib
{ nproc; lscpu | grep "Model name"; uname -r; date -u; } > $OUT/host.txt 2>&1
for l in 2 3 4; do $D/peers/prep $D/data/armadillo.off $W/a$l.bin $l loop >/dev/null && $D/peers/bin2obj $W/a$l.bin $W/a$l.obj >/dev/null; done
run() { # mode mesh threads round
  rm -f $W/o.vgeo $W/s.json; sync
  if [ $1 = merge ]; then E="VGEO_MERGE=1 VGEO_MS=9"; else E=""; fi
  env $E $D/vgeo_new build $W/$2.obj -o $W/o.vgeo --threads $3 --stats $W/s.json > /dev/null 2>$W/err || { echo "FAIL $*"; cat $W/err; }
  echo "{\"bin\":\"$1\",\"mesh\":\"$2\",\"threads\":$3,\"round\":$4,\"stats\":$(tr -d '\n' < $W/s.json)}" >> $OUT/runs.jsonl
  cmp -s $W/o.vgeo $W/ref_$1_$2.vgeo 2>/dev/null || { [ -f $W/ref_$1_$2.vgeo ] && echo "DIFF $*" >> $OUT/host.txt || cp $W/o.vgeo $W/ref_$1_$2.vgeo; }
}
peer() { sync; echo "{\"bin\":\"$1\",\"mesh\":\"$2\",\"threads\":$3,\"round\":$4,\"peer\":$($D/peers/$1 $W/$2.bin $3 1 | tail -1)}" >> $OUT/runs.jsonl; }
rounds() { # mesh count
  for r in $(seq 1 $2); do
    for b in metis merge; do run $b $1 16 $r; done; peer nvlod_driver $1 16 $r; for b in merge metis; do run $b $1 16 $r; done
    for b in metis merge; do run $b $1 1 $r; done; peer clod_driver $1 1 $r
  done
}
rounds a2 6; rounds a3 2; rounds a4 1
grep -c . $OUT/runs.jsonl

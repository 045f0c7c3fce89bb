#!/bin/bash
# Loop x2 on one thread and 16, eight rounds alternating, with the host's scaling probe before and after.
set -u
D=$(pwd)/.dev; W=/tmp/w; mkdir -p $W; export LD_LIBRARY_PATH=$D/lib
{ nproc; lscpu | grep -E "Model name"; uname -r; date -u; } > $OUT/host.txt 2>&1
$D/scaling_probe > $OUT/probe-before.txt 2>&1
$D/peers/prep $D/data/armadillo.off $W/a2.bin 2 loop >/dev/null && $D/peers/bin2obj $W/a2.bin $W/a2.obj >/dev/null
for r in 1 2 3 4 5 6 7 8; do for t in 1 16; do
  rm -f $W/o.vgeo $W/s.json; sync
  $D/vgeo_new build $W/a2.obj -o $W/o.vgeo --threads $t --stats $W/s.json > /dev/null 2>$W/err || cat $W/err
  echo "{\"bin\":\"vgeo_new\",\"mesh\":\"a2\",\"subdiv\":0,\"threads\":$t,\"round\":$r,\"stats\":$(tr -d '\n' < $W/s.json)}" >> $OUT/runs.jsonl
done; done
$D/scaling_probe > $OUT/probe-after.txt 2>&1
date -u >> $OUT/host.txt

#!/bin/bash
# The goals against the peers with every builder alternating: armadillo Loop x2 in six rounds and x3
# in three, each round clusterlod and vgeo_new on one thread, vgeo_new and nv_cluster_lod_builder on
# 16, the order turning by round. Run from the repository root with .dev/ as
# bench/device_build_runs.sh describes, plus .dev/scaling_probe; results under $OUT.
set -u
. bench/device_build_runs.sh  # D, W, host.txt, run(), prepLoops, peer()
prepLoops 2 3
round() { # mesh round
  if [ $(($2 % 2)) = 1 ]; then
    peer clod_driver $1 1 $2; run vgeo_new $W/$1.obj 0 1 $2 $1; run vgeo_new $W/$1.obj 0 16 $2 $1; peer nvlod_driver $1 16 $2
  else
    run vgeo_new $W/$1.obj 0 1 $2 $1; peer clod_driver $1 1 $2; peer nvlod_driver $1 16 $2; run vgeo_new $W/$1.obj 0 16 $2 $1
  fi
}
$D/scaling_probe > $OUT/probe-before.txt 2>&1
for r in 1 2 3 4 5 6; do round a2 $r; done
for r in 1 2 3; do round a3 $r; done
$D/scaling_probe > $OUT/probe-after.txt 2>&1
grep -c . $OUT/runs.jsonl; date -u >> $OUT/host.txt

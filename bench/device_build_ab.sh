#!/bin/bash
# .dev/vgeo_head against .dev/vgeo_new (or the builds of .dev/ that BINS names) on one device host,
# their order turning by round: armadillo Loop x2 on one thread (ONE_THREAD_ROUNDS, default four) and
# 16 (eight), Loop x3 on one thread (two) and 16 (four), armadillo's cage at each level of CAGE_LEVELS
# (default 2) on 16 threads (four); with PROBE=1 the host's scaling probe (.dev/scaling_probe, to
# probe.txt); unless PEERS=0, clusterlod (one thread) and nv_cluster_lod_builder (16) once a mesh. Output bytes compared (a DIFF line in host.txt when they
# differ). Run from the repository root with .dev/ as bench/device_build_runs.sh describes; results
# under $OUT, for bench/summarize_runs.py.
set -u
. bench/device_build_runs.sh  # D, W, host.txt, run(), prepLoops, peer()
prepLoops 2 3
bins=(${BINS:-vgeo_head vgeo_new})
order() { for i in "${!bins[@]}"; do echo ${bins[$(((i + $1 - 1) % ${#bins[@]}))]}; done; }  # round $1's
for r in $(seq 1 8); do
  [ $r -le ${ONE_THREAD_ROUNDS:-4} ] && for b in $(order $r); do run $b $W/a2.obj 0 1 $r a2; done
  for b in $(order $r); do run $b $W/a2.obj 0 16 $r a2; done
done
for r in 1 2 3 4; do
  [ $r -le 2 ] && for b in $(order $r); do run $b $W/a3.obj 0 1 $r a3; done
  for b in $(order $r); do run $b $W/a3.obj 0 16 $r a3; done
  for s in ${CAGE_LEVELS:-2}; do for b in $(order $r); do run $b $D/data/armadillo.off $s 16 $r cage; done; done
done
[ "${PROBE:-0}" = 1 ] && $D/scaling_probe > $OUT/probe.txt 2>&1
[ "${PEERS:-1}" = 1 ] && for m in a2 a3; do peer clod_driver $m 1 1; peer nvlod_driver $m 16 1; done
grep -c . $OUT/runs.jsonl; date -u >> $OUT/host.txt

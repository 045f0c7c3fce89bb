#!/bin/bash
# Freed memory kept for reuse on many threads: one binary (vgeo_new) run as it is (vgeo_base) and with
# VGEO_KEEP=1 (vgeo_keep: above four threads, mallopt's mmap threshold at 32 MiB and trim threshold at
# 1 GiB, so that the steps reuse what earlier ones freed instead of faulting in fresh pages).
# Eight rounds, the two's order alternating: armadillo Loop x2 on one thread (vgeo_base) and on 8 and
# 16 (both), x3 on 16 (rounds 1-4), the cage at --subdiv 2 and 3 on 16 (rounds 1-3). Setup as
# results/build-2026-12-01/run.sh.
set -u
. bench/device_build_runs.sh  # D, W, host.txt and run()
A=$D/data/armadillo.off
for l in 2 3; do $D/peers/prep $A $W/a$l.bin $l loop >/dev/null && $D/peers/bin2obj $W/a$l.bin $W/a$l.obj >/dev/null; done
ln -sf vgeo_new $D/vgeo_base
printf '#!/bin/sh\nVGEO_KEEP=1 exec %s "$@"\n' $D/vgeo_new > $D/vgeo_keep; chmod +x $D/vgeo_keep
for r in 1 2 3 4 5 6 7 8; do
  if [ $((r % 2)) = 1 ]; then bins="vgeo_base vgeo_keep"; else bins="vgeo_keep vgeo_base"; fi
  run vgeo_base $W/a2.obj 0 1 $r a2
  for b in $bins; do
    for t in 16 8; do run $b $W/a2.obj 0 $t $r a2; done
    [ $r -le 4 ] && run $b $W/a3.obj 0 16 $r a3
    [ $r -le 3 ] && for s in 2 3; do run $b $A $s 16 $r cage; done
  done
done
grep -c . $OUT/runs.jsonl; date -u >> $OUT/host.txt

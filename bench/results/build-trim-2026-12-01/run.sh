#!/bin/bash
# The allocator's free pages given back at four points of a build (vgeo_new) against the commit before
# (vgeo_head): armadillo Loop x2 on 1, 2, 4, 8 and 16 threads (four rounds, the binaries' order
# alternating), Loop x3 on 16 threads (three) and one (one), the cage at --subdiv 1, 2, 3 on 16 threads
# (three); output bytes compared. Binaries, libraries, peers and armadillo under .dev/ as run.sh of
# build-2026-12-01.
set -u
. bench/device_build_runs.sh  # D, W, host.txt and run()
A=$D/data/armadillo.off
for l in 2 3; do $D/peers/prep $A $W/a$l.bin $l loop >/dev/null && $D/peers/bin2obj $W/a$l.bin $W/a$l.obj >/dev/null; done
for r in 1 2 3 4; do
  if [ $((r % 2)) = 1 ]; then bins="vgeo_head vgeo_new"; else bins="vgeo_new vgeo_head"; fi
  for b in $bins; do
    for t in 16 1 2 4 8; do run $b $W/a2.obj 0 $t $r a2; done
    if [ $r -le 3 ]; then
      run $b $W/a3.obj 0 16 $r a3
      for s in 1 2 3; do run $b $A $s 16 $r cage; done
    fi
    [ $r = 1 ] && run $b $W/a3.obj 0 1 $r a3
  done
done
grep -c . $OUT/runs.jsonl; date -u >> $OUT/host.txt

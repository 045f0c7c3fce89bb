#!/bin/bash
# The cage path at 16 threads (armadillo --subdiv 1/2/3) and on one and two (--subdiv 2, the order of the
# two binaries alternating by round): vgeo_head against vgeo_new, output bytes compared; then perf
# timelines of vgeo_new at 16 threads (--subdiv 3 and 2), for bench/perf_timeline.py. Run from the
# repository root with the binaries, their libraries, armadillo.off and perf (with its libraries, under
# .dev/perf) under .dev/; results under $OUT.
set -u
. bench/device_build_runs.sh  # D, W, host.txt and run()
A=$D/data/armadillo.off
for r in 1 2 3; do
  for s in 3 2 1; do for b in vgeo_head vgeo_new vgeo_new vgeo_head; do run $b $A $s 16 $r cage; done; done
done
for r in 1 2 3 4; do
  if [ $((r % 2)) = 1 ]; then order="vgeo_head vgeo_new"; else order="vgeo_new vgeo_head"; fi
  for b in $order; do run $b $A 2 1 $r cage; done
  for b in $order; do run $b $A 2 2 $r cage; done
done
P="env LD_LIBRARY_PATH=$D/perf:$D/lib $D/perf/perf"
for s in 3 2; do
  $P record -e cpu-clock -F 4000 -o $W/p.data $D/vgeo_new build $A -o $W/o.vgeo --subdiv $s --threads 16 > /dev/null 2>&1
  $P script -i $W/p.data -F tid,time,ip,sym,dso --no-demangle 2>/dev/null | gzip > $W/p16_s$s.txt.gz
  cp $W/p16_s$s.txt.gz $OUT/ && python3 bench/perf_timeline.py $W/p16_s$s.txt.gz 2 4000 > $OUT/timeline_s${s}_16t_2ms.txt 2>&1
done
grep -c . $OUT/runs.jsonl; date -u >> $OUT/host.txt

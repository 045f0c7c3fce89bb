#!/bin/bash
# As run-points.sh, on the binary that gives nothing back on one thread and has no trim points 4 and 5:
# masks 0, 9 (after repair, before the layout), 11 (and before a cage's normals), 13 (and after the
# leaf clusters), 15; armadillo Loop x2 on 16, 8 and 2 threads (four rounds, the masks' order turning),
# x3 and the cage at --subdiv 2 on 16 threads (three).
set -u
. bench/device_build_runs.sh  # D, W, host.txt and run()
A=$D/data/armadillo.off
for l in 2 3; do $D/peers/prep $A $W/a$l.bin $l loop >/dev/null && $D/peers/bin2obj $W/a$l.bin $W/a$l.obj >/dev/null; done
for m in 0 9 11 13 15; do printf '#!/bin/sh\nVGEO_TRIM_AT=%s exec %s "$@"\n' $m $D/vgeo_mask > $D/vgeo_m$m; chmod +x $D/vgeo_m$m; done
for r in 1 2 3 4; do
  set -- 0 9 11 13 15; shift $((r % 5)); list=$(echo "$* 0 9 11 13 15" | cut -d' ' -f1-5)
  for m in $list; do
    for t in 16 8 2; do run vgeo_m$m $W/a2.obj 0 $t $r a2; done
    if [ $r -le 3 ]; then run vgeo_m$m $W/a3.obj 0 16 $r a3; run vgeo_m$m $A 2 16 $r cage; fi
  done
done
grep -c . $OUT/runs.jsonl; date -u >> $OUT/host.txt

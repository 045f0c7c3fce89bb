#!/bin/bash
# Which points of the build give the free pages back: one binary (vgeo_mask) whose VGEO_TRIM_AT bit mask
# picks them (bit 0 after repair, 1 before the shading normals of a subdivided cage, 2 after the leaf
# clusters, 3 before the layout, 4 before the leaf clusters, 5 after every round), masks 0, 15, 31, 47
# and 63; armadillo Loop x2 on 16, 8 and 1 threads, x3 and the cage at --subdiv 2 on 16 (three rounds,
# the masks' order turning by round); then one traced run of each mask on Loop x2 at 16 threads.
set -u
. bench/device_build_runs.sh  # D, W, host.txt and run()
A=$D/data/armadillo.off
for l in 2 3; do $D/peers/prep $A $W/a$l.bin $l loop >/dev/null && $D/peers/bin2obj $W/a$l.bin $W/a$l.obj >/dev/null; done
for m in 0 15 31 47 63; do printf '#!/bin/sh\nVGEO_TRIM_AT=%s exec %s "$@"\n' $m $D/vgeo_mask > $D/vgeo_m$m; chmod +x $D/vgeo_m$m; done
for r in 1 2 3; do
  set -- 0 15 31 47 63; shift $((r % 5)); list=$(echo "$* 0 15 31 47 63" | cut -d' ' -f1-5)
  for m in $list; do
    for t in 16 8; do run vgeo_m$m $W/a2.obj 0 $t $r a2; done
    [ $r = 1 ] && run vgeo_m$m $W/a2.obj 0 1 $r a2
    run vgeo_m$m $W/a3.obj 0 16 $r a3
    run vgeo_m$m $A 2 16 $r cage
  done
done
for m in 0 15 31 47 63; do rm -f $W/o.vgeo; VGEO_RSS_TRACE=1 $D/vgeo_m$m build $W/a2.obj -o $W/o.vgeo --threads 16 > $OUT/trace_m$m.txt 2>&1; done
grep -c . $OUT/runs.jsonl; date -u >> $OUT/host.txt

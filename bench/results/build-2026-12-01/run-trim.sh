#!/bin/bash
# glibc malloc's trim threshold fixed at 128 KB (its mmap threshold then stays at 128 KB too) against
# the default on 1, 2, 4 and 8 threads: armadillo Loop x2 (four rounds), x3 and the cage at --subdiv 2
# (two; x3 from 2 threads up), the two settings' order alternating; output bytes compared. As run.sh.
set -u
. bench/device_build_runs.sh  # D, W, host.txt and run()
A=$D/data/armadillo.off
for l in 2 3; do $D/peers/prep $A $W/a$l.bin $l loop >/dev/null && $D/peers/bin2obj $W/a$l.bin $W/a$l.obj >/dev/null; done
mk() { printf '#!/bin/sh\nGLIBC_TUNABLES=glibc.malloc.hugetlb=1%s exec %s "$@"\n' "$2" $D/vgeo_new > $D/vgeo_$1; chmod +x $D/vgeo_$1; }
mk default ""; mk trim128k ":glibc.malloc.trim_threshold=131072"
for r in 1 2 3 4; do
  [ $((r % 2)) = 1 ] && list="default trim128k" || list="trim128k default"
  for t in 1 2 4 8; do for v in $list; do
    run vgeo_$v $W/a2.obj 0 $t $r a2
    if [ $r -le 2 ]; then [ $t -gt 1 ] && run vgeo_$v $W/a3.obj 0 $t $r a3; run vgeo_$v $A 2 $t $r cage; fi
  done; done
done
grep -c . $OUT/runs.jsonl; date -u >> $OUT/host.txt

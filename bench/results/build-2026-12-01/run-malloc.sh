#!/bin/bash
# glibc malloc's trim and mmap thresholds (fixed ones turn off its dynamic thresholds, which after the
# first large free keep up to 64 MB free in every thread's arena): vgeo_new under each setting against
# the default, armadillo Loop x2 (four rounds), x3 and the cage at --subdiv 2 and 3 (three), on 16
# threads and 2, the settings' order turning by round; output bytes compared. Setup as run.sh.
set -u
. bench/device_build_runs.sh  # D, W, host.txt and run()
A=$D/data/armadillo.off
for l in 2 3; do $D/peers/prep $A $W/a$l.bin $l loop >/dev/null && $D/peers/bin2obj $W/a$l.bin $W/a$l.obj >/dev/null; done
mk() { printf '#!/bin/sh\nGLIBC_TUNABLES=glibc.malloc.hugetlb=1%s exec %s "$@"\n' "$2" $D/vgeo_new > $D/vgeo_$1; chmod +x $D/vgeo_$1; }
mk default ""; mk trim128k ":glibc.malloc.trim_threshold=131072"; mk trim1m ":glibc.malloc.trim_threshold=1048576"
mk mmap1m ":glibc.malloc.mmap_threshold=1048576"; mk trim128k_mmap32m ":glibc.malloc.trim_threshold=131072:glibc.malloc.mmap_threshold=33554432"
all="default trim128k trim1m mmap1m trim128k_mmap32m"
for r in 1 2 3 4; do
  set -- $all $all; shift $((r % 5)); list=$(echo $* | cut -d' ' -f1-5)
  for v in $list; do
    run vgeo_$v $W/a2.obj 0 16 $r a2; run vgeo_$v $W/a2.obj 0 2 $r a2
    if [ $r -le 3 ]; then run vgeo_$v $W/a3.obj 0 16 $r a3; run vgeo_$v $A 2 16 $r cage; run vgeo_$v $A 3 16 $r cage; fi
  done
done
grep -c . $OUT/runs.jsonl; date -u >> $OUT/host.txt

#!/bin/bash
# A/B on the device host: base vs new binary, each with and without THP through glibc's malloc.
set -u
D=$(pwd)/.dev; W=/tmp/w; mkdir -p $W; export LD_LIBRARY_PATH=$D/lib
{ nproc; lscpu | grep "Model name"; ldd --version | head -1; cat /sys/kernel/mm/transparent_hugepage/enabled /sys/kernel/mm/transparent_hugepage/defrag; uname -r; free -g | head -2; } > $OUT/host.txt 2>&1
$D/peers/prep $D/data/armadillo.off $W/a2.bin 2 loop >/dev/null && $D/peers/bin2obj $W/a2.bin $W/a2.obj >/dev/null
$D/peers/prep $D/data/armadillo.off $W/a3.bin 3 loop >/dev/null && $D/peers/bin2obj $W/a3.bin $W/a3.obj >/dev/null
run() { # bin thp mesh threads tag
  rm -f $W/o.vgeo $W/s.json; sync
  if [ $2 = 1 ]; then T=glibc.malloc.hugetlb=1; else T=; fi
  GLIBC_TUNABLES=$T $D/$1 build $W/$3.obj -o $W/o.vgeo --threads $4 --stats $W/s.json > /dev/null 2>$W/err || { echo "FAIL $*"; cat $W/err; }
  echo "{\"bin\":\"$1\",\"thp\":$2,\"mesh\":\"$3\",\"threads\":$4,\"round\":$5,\"stats\":$(tr -d '\n' < $W/s.json)}" >> $OUT/runs.jsonl
  cmp -s $W/o.vgeo $W/ref_$3.vgeo 2>/dev/null || { [ -f $W/ref_$3.vgeo ] && echo "DIFF $*" >> $OUT/host.txt || cp $W/o.vgeo $W/ref_$3.vgeo; }
}
for r in 1 2 3 4 5; do
  for b in vgeo_base vgeo_new; do for t in 0 1; do run $b $t a2 16 $r; run $b $t a3 16 $r; done; done
  if [ $r -le 2 ]; then for b in vgeo_base vgeo_new; do for t in 0 1; do run $b $t a2 1 $r; done; done; fi
done
run vgeo_base 0 a3 1 1; run vgeo_base 1 a3 1 1
grep -c . $OUT/runs.jsonl

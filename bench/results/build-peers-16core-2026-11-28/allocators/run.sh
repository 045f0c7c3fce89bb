#!/bin/bash
# Allocators on the device host: glibc's malloc against mimalloc, jemalloc and tcmalloc (LD_PRELOAD).
set -u
D=$(pwd)/.dev; W=/tmp/w; mkdir -p $W; export LD_LIBRARY_PATH=$D/lib
{ nproc; lscpu | grep "Model name"; uname -r; } > $OUT/host.txt 2>&1
$D/peers/prep $D/data/armadillo.off $W/a2.bin 2 loop >/dev/null && $D/peers/bin2obj $W/a2.bin $W/a2.obj >/dev/null
$D/peers/prep $D/data/armadillo.off $W/a3.bin 3 loop >/dev/null && $D/peers/bin2obj $W/a3.bin $W/a3.obj >/dev/null
run() { # alloc mesh threads round
  rm -f $W/o.vgeo $W/s.json; sync
  P=; [ $1 != glibc ] && P=$D/alloc/$1
  LD_PRELOAD=$P $D/vgeo_base build $W/$2.obj -o $W/o.vgeo --threads $3 --stats $W/s.json > /dev/null 2>$W/err || { echo "FAIL $*"; cat $W/err; }
  echo "{\"bin\":\"$1\",\"thp\":0,\"mesh\":\"$2\",\"threads\":$3,\"round\":$4,\"stats\":$(tr -d '\n' < $W/s.json)}" >> $OUT/runs.jsonl
  cmp -s $W/o.vgeo $W/ref_$2.vgeo 2>/dev/null || { [ -f $W/ref_$2.vgeo ] && echo "DIFF $*" >> $OUT/host.txt || cp $W/o.vgeo $W/ref_$2.vgeo; }
}
A="glibc libmimalloc.so.2 libjemalloc.so.2 libtcmalloc_minimal.so.4"
for r in 1 2 3 4 5; do
  for a in $A; do run $a a2 16 $r; [ $r -le 3 ] && run $a a3 16 $r; done
  if [ $r -le 2 ]; then for a in $A; do run $a a2 1 $r; done; fi
done
grep -c . $OUT/runs.jsonl

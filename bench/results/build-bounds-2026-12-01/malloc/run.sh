#!/bin/bash
# Whether glibc's heap trimming slows the 16-thread tail: vgeo_tr (a line a round) on Loop x2 at 16
# threads as it is and with trimming held off (GLIBC_TUNABLES trim_threshold 1 GB, top_pad 16 MB),
# alternating, six rounds; one thread twice each. Run from the repository root with .dev/ as
# bench/device_build_runs.sh describes; results under $OUT.
set -u
. bench/device_build_runs.sh
A=$D/data/armadillo.off
$D/peers/prep $A $W/a2.bin 2 loop >/dev/null && $D/peers/bin2obj $W/a2.bin $W/a2.obj >/dev/null
T=glibc.malloc.trim_threshold=1073741824:glibc.malloc.top_pad=16777216
one() { # variant threads round
  rm -f $W/o.vgeo; sync
  if [ $1 = held ]; then e="GLIBC_TUNABLES=$T"; else e="X=1"; fi
  env $e $D/vgeo_tr build $W/a2.obj -o $W/o.vgeo --threads $2 --stats $W/s.json 2>&1 >/dev/null | grep TR > $W/tr.txt
  { echo "== $1 $2 threads round $3"; cat $W/tr.txt; } >> $OUT/rounds.txt
  echo "{\"variant\":\"$1\",\"threads\":$2,\"round\":$3,\"stats\":$(tr -d '\n' < $W/s.json)}" >> $OUT/runs.jsonl
}
for r in 1 2 3 4 5 6; do
  if [ $((r % 2)) = 1 ]; then o="plain held"; else o="held plain"; fi
  for v in $o; do one $v 16 $r; done
  [ $r -le 2 ] && for v in $o; do one $v 1 $r; done
done
$D/scaling_probe > $OUT/probe.txt 2>&1
date -u >> $OUT/host.txt

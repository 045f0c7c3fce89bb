#!/bin/bash
. bench/device_build_runs.sh
prepLoops 2 3
for m in a2 a3; do for r in 1 2 3 4 5 6; do
  rm -f $W/o.vgeo; sync
  $D/vgeo_new build $W/$m.obj -o $W/o.vgeo --threads 16 -q --stats $W/s.json 2> $W/err
  echo "== $m $r $(python3 -c "import json; s=json.load(open('$W/s.json')); print(round(s['total_seconds']*1000,2), round(s['build_seconds']*1000,2), round(s['stage_seconds']['load']*1000,2), round(s['stage_seconds']['repair']*1000,2), round(s['stage_seconds']['write']*1000,2))")" >> $OUT/gaps.txt
  grep "^T" $W/err >> $OUT/gaps.txt
done; done

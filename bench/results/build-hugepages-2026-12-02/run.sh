#!/bin/bash
# Four builds alternating by round (the order turns each round): vgeo_head (5484258), vgeo_new (large
# fill-later arrays advised onto transparent huge pages, and the last mesh's arrays freed beside the
# commit), and each of them with GLIBC_TUNABLES=glibc.malloc.hugetlb=1 in the environment
# (vgeo_head_env, vgeo_new_env, wrappers written here; vgeo sets that tunable itself where the host
# gives huge pages on request, so these build as their baselines). Armadillo Loop x2 on one
# thread (three rounds) and 16 (eight), Loop x3 on one (two) and 16 (four), the cage at --subdiv 2 on
# 16 (four). Run from the repository root with .dev/ as bench/device_build_runs.sh describes.
set -u
. bench/device_build_runs.sh  # D, W, host.txt, run(), prepLoops
for b in vgeo_head vgeo_new; do
  printf '#!/bin/sh\nGLIBC_TUNABLES=glibc.malloc.hugetlb=1 exec "$(dirname "$0")/%s" "$@"\n' $b > $D/${b}_env
  chmod +x $D/${b}_env
done
cat /sys/kernel/mm/transparent_hugepage/enabled /sys/kernel/mm/transparent_hugepage/defrag > $OUT/thp.txt
prepLoops 2 3
bins=(vgeo_head vgeo_new vgeo_head_env vgeo_new_env)
order() { for i in 0 1 2 3; do echo ${bins[$(( (i + $1) % 4 ))]}; done; }
for r in $(seq 1 8); do
  [ $r -le 3 ] && for b in $(order $r); do run $b $W/a2.obj 0 1 $r a2; done
  for b in $(order $r); do run $b $W/a2.obj 0 16 $r a2; done
done
for r in 1 2 3 4; do
  [ $r -le 2 ] && for b in $(order $r); do run $b $W/a3.obj 0 1 $r a3; done
  for b in $(order $r); do run $b $W/a3.obj 0 16 $r a3; done
  for b in $(order $r); do run $b $D/data/armadillo.off 2 16 $r cage; done
done
grep -c . $OUT/runs.jsonl; date -u >> $OUT/host.txt

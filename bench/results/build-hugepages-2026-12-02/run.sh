#!/bin/bash
# Four builds alternating by round (the order turns each round): vgeo_head (5484258), vgeo_new (large
# fill-later arrays advised onto transparent huge pages, and the last mesh's arrays freed beside the
# commit), and each of them with GLIBC_TUNABLES=glibc.malloc.hugetlb=1 in the environment
# (vgeo_head_env, vgeo_new_env, wrappers written here; vgeo sets that tunable itself where the host
# gives huge pages on request, so these build as their baselines). Armadillo Loop x2 on one
# thread (three rounds) and 16 (eight), Loop x3 on one (two) and 16 (four), the cage at --subdiv 2 on
# 16 (four), by bench/device_build_ab.sh (as run, each round's order began one build later). Run from
# the repository root with .dev/ as bench/device_build_runs.sh describes.
for b in vgeo_head vgeo_new; do
  printf '#!/bin/sh\nGLIBC_TUNABLES=glibc.malloc.hugetlb=1 exec "$(dirname "$0")/%s" "$@"\n' $b > .dev/${b}_env
  chmod +x .dev/${b}_env
done
cat /sys/kernel/mm/transparent_hugepage/enabled /sys/kernel/mm/transparent_hugepage/defrag > $OUT/thp.txt
BINS="vgeo_head vgeo_new vgeo_head_env vgeo_new_env" ONE_THREAD_ROUNDS=3 PEERS=0 bash bench/device_build_ab.sh

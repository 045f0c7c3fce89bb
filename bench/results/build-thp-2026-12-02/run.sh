#!/bin/bash
# vgeo_head (5484258) against the same binary with GLIBC_TUNABLES=glibc.malloc.hugetlb=1 set in its
# environment (.dev/vgeo_new: a wrapper), which vgeo sets itself where the host gives huge pages on
# request: an A/A run. By bench/device_build_ab.sh, with the host's huge page settings and probe. Run from the
# repository root with .dev/ as bench/device_build_runs.sh describes; results under $OUT.
printf '#!/bin/sh\nGLIBC_TUNABLES=glibc.malloc.hugetlb=1 exec "$(dirname "$0")/vgeo_head" "$@"\n' > .dev/vgeo_new
chmod +x .dev/vgeo_new
cat /sys/kernel/mm/transparent_hugepage/enabled /sys/kernel/mm/transparent_hugepage/defrag > $OUT/thp.txt 2>&1
PROBE=1 bash bench/device_build_ab.sh
grep -E "AnonHugePages|HugePages_Total" /proc/meminfo >> $OUT/thp.txt

#!/usr/bin/env bash
# Worker profile of the persistent traversal on an NVIDIA machine (setup as bench/gpu_run.sh): `vgeo bench
# cut --profile-workers` on armadillo --subdiv 2 at 1920x1080, persistent only, sizes from $SIZES (default
# 100,1000,100000). Writes $OUT/profile.json; prints one line a record: time, span, first item, last item
# end, tail (device-clock ticks: ns on NVIDIA), median claim / take / rounds of iterations with items.
set -uo pipefail
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
export LD_LIBRARY_PATH=$PWD/.dev/lib
V=.dev/vgeo
$V build .dev/data/armadillo.off --subdiv 2 -o /tmp/arm2.vgeo --threads 16 -q > /dev/null
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $OUT/gpu.txt 2>&1
$V bench cut /tmp/arm2.vgeo -o $OUT/profile.json --frames 10 --size 1920x1080 --sizes ${SIZES:-100,1000,100000} \
  --traversals persistent --profile-workers > $OUT/log.txt 2>&1
python3 - "$OUT/profile.json" <<'PY'
import json, sys
for r in json.load(open(sys.argv[1])):
    p = r.get("worker_profile", {})
    print("%-7s %6d %-8s tau %g  %.3f ms  span %s first %s last %s tail %s  claim %s take %s rounds %s  items/it %.1f polls %s%s" % (
        r["layout"], r["instances"], r["camera"], r["tau"], r["traversal_ms"], p.get("span_ticks"), p.get("first_item_ticks"),
        p.get("last_item_end_ticks"), p.get("tail_ticks"), p.get("claim_ticks_median"), p.get("take_ticks_median"),
        p.get("rounds_ticks_median"), p.get("items_per_iteration", 0.0), p.get("polls"), " TRUNCATED" if p.get("truncated") else ""))
PY

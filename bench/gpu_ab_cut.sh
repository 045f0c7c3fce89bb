#!/usr/bin/env bash
# A/B of two vgeo builds on the cut benchmark on an NVIDIA machine: .dev/vgeo_base and .dev/vgeo, runs
# alternated (base, new, base, new, ...) so that clock drift hits both alike. Each build makes its own
# armadillo --subdiv 2 file (the format may differ). Arguments go to `vgeo bench cut` (e.g. --sizes 100).
# Writes base-N.json and new-N.json to $OUT. Same setup as bench/gpu_run.sh.
set -uo pipefail
source bench/gpu_env.sh
ROUNDS=${ROUNDS:-2}
for b in base new; do
  V=.dev/vgeo; [ $b = base ] && V=.dev/vgeo_base
  $V build .dev/data/armadillo.off --subdiv 2 -o /tmp/arm2-$b.vgeo --threads 16 -q > /dev/null
done
for r in $(seq 1 $ROUNDS); do
  for b in base new; do
    V=.dev/vgeo; [ $b = base ] && V=.dev/vgeo_base
    $V bench cut /tmp/arm2-$b.vgeo -o $OUT/$b-$r.json --frames 10 --size 1920x1080 --traversals persistent,levels,flat "$@" 2>&1 | tail -2
  done
done

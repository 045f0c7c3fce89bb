#!/usr/bin/env bash
# The builder against its peers on one machine (bench/README.md, "Against the peer builders"): armadillo made denser by Loop
# subdivision (the peers' `prep`), `vgeo bench build` over thread counts (DAG and whole-build times,
# each step's seconds, peak memory) and the peer builders' drivers on the same meshes.
# Usage: bench/cpu_build_matrix.sh VGEO PEERS_BIN ARMADILLO.off OUT_DIR "THREADS" [LOOP_LEVELS...]
set -euo pipefail
V=$1 P=$2 mesh=$3 out=$4 threads=$5
shift 5
levels=${*:-2}
mkdir -p "$out"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
{ nproc; grep -m1 "model name" /proc/cpuinfo; $V --version; date -u +%FT%TZ; } > "$out/machine.txt"
for l in $levels; do
  $P/prep "$mesh" "$work/a$l.bin" "$l" loop > /dev/null
  $P/bin2obj "$work/a$l.bin" "$work/a$l.obj" > /dev/null
  $V bench build "$work/a$l.obj" --subdiv 0 --threads "${threads// /,}" --repeat 2 -o "$out/vgeo_a$l.json"
  for t in $threads; do
    $P/nvlod_driver "$work/a$l.bin" "$t" 2
    $P/clod_vklc_driver "$work/a$l.bin" "$t" 2
  done > "$out/peers_a$l.jsonl"
  $P/clod_driver "$work/a$l.bin" 1 2 >> "$out/peers_a$l.jsonl"
done

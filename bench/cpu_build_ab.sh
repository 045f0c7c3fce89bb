#!/usr/bin/env bash
# Two builds of vgeo alternating on one machine (bench/README.md, "Against the peer builders"): armadillo made denser by Loop
# subdivision (the peers' `prep`), each round building with OLD then NEW, then the peer that the
# thread count is measured against (clusterlod on one thread, nv_cluster_lod_builder on 16).
# Usage: bench/cpu_build_ab.sh OLD NEW PEERS_BIN ARMADILLO.off OUT_DIR "ONE_THREAD_LEVELS" \
#          "SIXTEEN_THREAD_LEVELS" ROUNDS
# Writes OUT_DIR/a{level}_{1,16}t_{old,new}_{round}.json (`vgeo bench build`) and the peers' .jsonl.
set -euo pipefail
OLD=$1 NEW=$2 P=$3 mesh=$4 out=$5 one=$6 sixteen=$7 rounds=$8
mkdir -p "$out"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
{ nproc; grep -m1 "model name" /proc/cpuinfo; date -u +%FT%TZ; echo "old: $($OLD --version)"; echo "new: $($NEW --version)"; } \
  > "$out/machine.txt"
for l in $(printf '%s\n' $one $sixteen | sort -u); do
  $P/prep "$mesh" "$work/a$l.bin" "$l" loop > /dev/null
  $P/bin2obj "$work/a$l.bin" "$work/a$l.obj" > /dev/null
done
# alternate LEVELS THREADS REPEAT PEER_DRIVER
alternate() {
  for l in $1; do
    for r in $(seq "$rounds"); do
      for side in old new; do
        bin=$OLD
        [ $side = new ] && bin=$NEW
        $bin bench build "$work/a$l.obj" --subdiv 0 --threads "$2" --repeat "$3" -o "$out/a${l}_${2}t_${side}_$r.json" > /dev/null
      done
      $P/$4 "$work/a$l.bin" "$2" "$3" >> "$out/a${l}_${2}t_$4.jsonl"
    done
  done
}
alternate "$one" 1 1 clod_driver
alternate "$sixteen" 16 2 nvlod_driver

#!/usr/bin/env bash
# vgeo bench cut on an NVIDIA machine (see bench/gpu_run.sh for what .gl/ and .dev/ must hold).
# Arguments replace the default `--flat-max-instances 100000`, e.g. the worker profile:
#   bash bench/gpu_bench_cut.sh --sizes 100,1000,100000 --traversals persistent --profile-workers
# which also prints the profiles a line a record (bench/print_worker_profile.py).
set -uo pipefail
source bench/gpu_env.sh
$V build .dev/data/armadillo.off --subdiv 2 -o /tmp/arm2.vgeo --threads 16 -q > /dev/null
args=("$@")
[ $# -eq 0 ] && args=(--flat-max-instances 100000)
$V bench cut /tmp/arm2.vgeo -o $OUT/cut.json --frames 10 --size 1920x1080 "${args[@]}" 2>&1 | tail -30
case " $* " in *" --profile-workers "*) python3 bench/print_worker_profile.py $OUT/cut.json ;; esac

#!/usr/bin/env bash
# vgeo bench cut on an NVIDIA machine (see bench/gpu_run.sh for what .gl/ and .dev/ must hold).
set -uo pipefail
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
export LD_LIBRARY_PATH=$PWD/.dev/lib
V=.dev/vgeo
$V build .dev/data/armadillo.off --subdiv 2 -o /tmp/arm2.vgeo --threads 16 -q > /dev/null
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $OUT/gpu.txt 2>&1
$V bench cut /tmp/arm2.vgeo -o $OUT/cut.json --frames 10 --size 1920x1080 --flat-max-instances 100000 2>&1 | tail -30

#!/bin/bash
# vgeo_head (6e90355) against vgeo_new on one device host, as results/build-2026-12-01/run.sh measures
# them (Loop x2 and x3 on one thread and 16 with the peers, the cages, the scaling probe): that script,
# run from the repository root with .dev/ as bench/device_build_runs.sh describes.
exec bash bench/results/build-2026-12-01/run.sh "$@"

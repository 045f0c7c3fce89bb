#!/bin/bash
# vgeo_head (6b24634) against vgeo_new (9d21f30) by bench/device_build_ab.sh with the host's scaling
# probe. Run from the repository root with .dev/ as bench/device_build_runs.sh describes, plus
# .dev/scaling_probe; results under $OUT.
PROBE=1 bash bench/device_build_ab.sh

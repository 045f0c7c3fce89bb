#!/bin/bash
# vgeo_head (5484258) against vgeo_new (the last mesh's arrays freed on a thread of their own beside
# the file's commit) by bench/device_build_ab.sh, with the host's scaling probe. Run from the
# repository root with .dev/ as bench/device_build_runs.sh describes; results under $OUT.
PROBE=1 bash bench/device_build_ab.sh

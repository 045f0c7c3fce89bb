#!/bin/bash
# vgeo_head (ee52b8c) against vgeo_new by bench/device_build_ab.sh. Run from the repository root with
# .dev/ as bench/device_build_runs.sh describes; results under $OUT.
bash bench/device_build_ab.sh

#!/bin/bash
# vgeo_head (325d154) against vgeo_new (the file written by up to four writer threads) by
# bench/device_build_ab.sh, the cage at --subdiv 2 and 3, with the host's scaling probe. Run from the
# repository root with .dev/ as bench/device_build_runs.sh describes, plus .dev/scaling_probe; results
# under $OUT.
CAGE_LEVELS="2 3" PROBE=1 bash bench/device_build_ab.sh

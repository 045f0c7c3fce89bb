#!/bin/bash
# vgeo_head (5484258) against vgeo_new (a text file parsed in sixteen pieces a thread instead of four,
# an OBJ's pieces of 256 KB or more instead of 1 MB: pieces.patch, not kept) by bench/device_build_ab.sh.
# Run from the repository root with .dev/ as bench/device_build_runs.sh describes; results under $OUT.
bash bench/device_build_ab.sh

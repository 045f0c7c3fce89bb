#!/bin/bash
# The default scene (horned_cube --subdiv 4, a 32 x 32 grid, 1280 x 720, lavapipe) built with METIS's
# groups (f6a3e4a, METIS_BIN) and with merged groups (f85ac1d or later, VGEO), each rendered at
# tau 0.5, 0.7, 1 and against its own tau 0.05 render (leaves and patches) from one camera: each
# build's grid spacing follows its own bounds, so images are compared within a build only.
set -eu
METIS_BIN=$1 VGEO=$2 OUT=$3
C=159.748108,37.2659378,159.748108,-29.1865292,0.043847084,-29.0720425
mkdir -p $OUT
$METIS_BIN build assets/horned_cube.obj --subdiv 4 -o $OUT/metis.vgeo -q
$VGEO build assets/horned_cube.obj --subdiv 4 -o $OUT/merge.vgeo -q
for b in metis merge; do for t in 0.05 0.5 0.7 1; do
  $VGEO render $OUT/$b.vgeo --grid 32 --size 1280x720 --tau $t --camera $C -o $OUT/${b}_$t.png --stats $OUT/${b}_$t.json >/dev/null
done; done
/usr/bin/python3 - "$OUT" <<'PY'
import json, sys
import matplotlib.image as im, numpy as np
out = sys.argv[1]
load = lambda f: im.imread(f'{out}/{f}.png')[..., :3]
for b in ['metis', 'merge']:
    ref = load(b + '_0.05')
    for t in ['0.5', '0.7', '1']:
        d = np.abs(load(f'{b}_{t}') - ref).max(axis=2)
        j = json.load(open(f'{out}/{b}_{t}.json'))
        print(f"{b} tau {t}: mean {d.mean():.5f}, px > 0.1: {(d > 0.1).sum()}, px > 0.25: {(d > 0.25).sum()}"
              f" | clusters {j['visible_clusters']}, triangles {j['triangles']}")
PY

#!/usr/bin/env bash
# Frame benchmarks with each rasterizer (default scene, 99,856 armadillos, cow close-up with its
# patches in compute, in the tessellator and as triangles; its pictures both ways under validation) and
# a cut benchmark, on a GPU machine set up as bench/README.md says (How to run; also .dev/data/cow.off);
# everything packed into $OUT/results.tgz, summaries on stdout.
set -uo pipefail
R=/tmp/results; mkdir -p $R
source bench/gpu_env.sh $R
D=.dev/data
$V build assets/horned_cube.obj --subdiv 4 -o /tmp/hc.vgeo -q --threads 16
$V build $D/cow.off --subdiv 1 -o /tmp/cow1.vgeo -q --threads 16
$V build $D/armadillo.off --subdiv 2 -o /tmp/arm2.vgeo -q --threads 16
$V bench frame /tmp/hc.vgeo -o $R/frame_default.json --grids 32 --sizes 1920x1080 --cameras corner,inside --frames 10 > $R/frame_default.log 2>&1
$V bench frame /tmp/arm2.vgeo -o $R/frame_arm.json --grids 316 --sizes 1920x1080 --cameras corner,inside --frames 10 > $R/frame_arm.log 2>&1
COW="/tmp/cow1.vgeo --camera 0.2,0.2,0.4,0,0,0 --tau 0.5 --size 1920x1080"
for i in 1 2; do for r in auto software hardware; do for np in "" --no-patches; do
  $V render $COW $np --raster $r --frames 30 -o /tmp/c.png --stats $R/cow_${r}${np}_$i.json > /dev/null 2>&1
  python3 -c "import json;d=json.load(open('$R/cow_${r}${np}_$i.json'));print('cow $r ${np:-patches}:', {k:d[k] for k in ['patches_drawn','software_patches','patch_triangles','triangles_drawn','software_triangles','triangle_cull_ms','raster_ms','draw_ms','resolve_ms','frame_ms']})"
done; done; done
for r in auto hardware; do
  validated $V render $COW --raster $r --validate --compare-cpu -o $R/cow_$r.png > $R/cow_validate_$r.log 2>&1
  echo "cow $r under validation: exit $?, $(grep -ci validation $R/cow_validate_$r.log) validation lines"
done
$V bench cut /tmp/arm2.vgeo -o $R/cut.json --sizes 100,100000 --layouts grid --taus 1 --traversals persistent --frames 20 > $R/cut.log 2>&1
cat $R/gpu.txt; cat $R/frame_default.log $R/frame_arm.log | grep instances; tail -12 $R/cut.log
tar czf $OUT/results.tgz -C /tmp results

#!/usr/bin/env bash
# gpu_regress.sh: every headline GPU number against its baseline, on an NVIDIA machine (the same .gl/ and
# .dev/ as bench/gpu_run.sh). Run it before resolving work that touches the builder, the file layout, the
# shaders or the renderer. The set:
#   cut:    `bench cut` of armadillo --subdiv 2 at 100, 10,000 and 100,000 instances, every camera, tau 1,
#           persistent traversal, occlusion off (the cut the CPU selects) and auto
#   frame:  the default scene (shipped cage --subdiv 4, 32 x 32) corner and inside; 99,856 armadillos
#           corner, inside and surface; the forest of 99,856 from the ground and above, occlusion
#           auto / on / off; the cow close-up (--subdiv 1, tau 0.5) with and without patches
#   checks: the 100-armadillo grid and the forest from the ground under the validation layer with
#           --compare-cpu (exit status and validation messages)
# Each number is compared with bench/gpu_baseline.json (bench/regress.py: more than 10% slower is a
# regression). With BASE=.dev/vgeo_base (another build, e.g. the last release's) both binaries run here,
# alternating, and the new one is compared with the base's run instead: the fairest comparison, the same
# host and clocks. ROUNDS (default 1) repeats the alternation; the minimum of the rounds is compared.
# Writes $OUT/new.json (merged records; copy it to bench/gpu_baseline.json to rebase), $OUT/base.json,
# $OUT/verdict.txt.
set -uo pipefail
source bench/gpu_env.sh
ROUNDS=${ROUNDS:-1}
D=.dev/data

# The set, by binary $1 into folder $2 (its own .vgeo files: the format may differ between builds).
run_set() {
  local bin=$1 out=$2 f=/tmp/$(basename $2)
  mkdir -p $out $f
  [ -f $f/arm2.vgeo ] || {
    $bin build $D/armadillo.off --subdiv 2 -o $f/arm2.vgeo --threads 16 -q
    $bin build assets/horned_cube.obj --subdiv 4 -o $f/hc.vgeo --threads 16 -q
    $bin build $D/cow.off --subdiv 1 -o $f/cow1.vgeo --threads 16 -q
  } > /dev/null
  local occ=(--occlusion off,auto)  # builds from before the option: their default (auto)
  $bin bench cut --help | grep -q -- --occlusion || occ=()
  $bin bench cut $f/arm2.vgeo -o $out/cut.json --sizes 100,10000,100000 --layouts grid --taus 1 \
    --traversals persistent "${occ[@]}" --frames 20 --size 1920x1080 2> $out/cut.log
  $bin bench frame $f/hc.vgeo -o $out/frame_default.json --grids 32 --sizes 1920x1080 --cameras corner,inside \
    --rasters auto --occlusion auto,off --frames 20 2> $out/frame_default.log
  $bin bench frame $f/arm2.vgeo -o $out/frame_armadillos.json --grids 316 --sizes 1920x1080 \
    --cameras corner,inside,surface --rasters auto --occlusion auto,off --frames 20 2> $out/frame_armadillos.log
  $bin bench frame $f/arm2.vgeo -o $out/frame_forest.json --layout forest --grids 316 --sizes 1920x1080 \
    --cameras ground,above --rasters auto --occlusion auto,on,off --frames 20 2> $out/frame_forest.log
  for np in patches no-patches; do
    flag=""; [ $np = no-patches ] && flag=--no-patches
    $bin render $f/cow1.vgeo --camera 0.2,0.2,0.4,0,0,0 --tau 0.5 --size 1920x1080 --frames 30 $flag \
      -o /tmp/cow.png --stats $out/cow_$np.json > /dev/null 2>&1
  done
}

for r in $(seq 1 $ROUNDS); do
  [ -n "${BASE:-}" ] && run_set $BASE /tmp/regress/base-$r
  run_set $V /tmp/regress/new-$r
done

for who in new base; do
  [ -d /tmp/regress/$who-1 ] || continue
  for r in $(seq 1 $ROUNDS); do python3 bench/regress.py merge /tmp/regress/$who-$r -o /tmp/regress/$who-$r.json > /dev/null; done
  python3 bench/regress.py minimum $OUT/$who.json /tmp/regress/$who-*.json
done

# The validation checks (the new binary only).
checks=0
f=/tmp/new-1  # run_set's files of the new binary
validated $V render $f/arm2.vgeo --grid 10 --size 1280x720 --validate --compare-cpu -o /tmp/v1.png > /tmp/v1.log 2>&1
s1=$?
validated $V render $f/arm2.vgeo --layout forest --grid 316 --size 1920x1080 --frames 4 --occlusion on \
  --camera "$(python3 -c "import json;print([r['camera_option'] for r in json.load(open('/tmp/regress/new-1/frame_forest.json')) if r['camera']=='ground'][0])")" \
  --validate --compare-cpu -o /tmp/v2.png > /tmp/v2.log 2>&1
s2=$?
{
  cat $OUT/gpu.txt
  for i in 1 2; do
    s=s$i
    echo "validation run $i: exit ${!s}, $(grep -ci 'validation' /tmp/v$i.log) lines naming validation"
    grep -iE "validation|VUID|differ" /tmp/v$i.log | head -3
    [ ${!s} -eq 0 ] || checks=1
  done
  against=bench/gpu_baseline.json
  [ -f $OUT/base.json ] && against=$OUT/base.json
  if [ -f $against ]; then
    python3 bench/regress.py compare $against $OUT/new.json
  else
    echo "verdict: NO BASELINE: commit \$OUT/new.json as bench/gpu_baseline.json (the card above) to start one"
  fi
} 2>&1 | tee $OUT/verdict.txt
cat /tmp/regress/new-1/*.log | grep -E "instances" | tee $OUT/new-log.txt > /dev/null

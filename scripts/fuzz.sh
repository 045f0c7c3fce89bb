#!/usr/bin/env bash
# Runs vgeo's libFuzzer targets (tests/fuzz: one a reader, and the whole builder) under AddressSanitizer
# and UndefinedBehaviorSanitizer, SECONDS each (default 60), from seed corpora of the tests' inputs,
# CGAL's demo meshes and Debian's assimp glTFs. A crash, a sanitizer report, a hang over 5 s or memory
# over 2 GB fails the run; libFuzzer leaves the input that did it as crash-* / timeout-* / oom-* in
# build-asan/fuzz/. Corpora grow in build-asan/fuzz/TARGET between runs; the counts of the last run are
# in build-asan/fuzz/counts.txt (docs/fuzzing.md keeps those of the long runs).
#
#   bash scripts/fuzz.sh [SECONDS] [TARGET ...]        each target for SECONDS (default 60)
#   bash scripts/fuzz.sh --runs N [TARGET ...]         each target for N executions (the long run:
#                                                      N = 1000000, about 2 1/2 hours on one core)
# targets: obj off ply gltf glb vgeo json pipeline
set -euo pipefail
cd "$(dirname "$0")/.."
if [ "${1:-}" = "--runs" ]; then
  limit=(-runs="$2")
  what="$2 executions"
  shift 2
else
  limit=(-max_total_time="${1:-60}")
  what="${1:-60} s"
  shift || true
fi
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(obj off ply gltf glb vgeo json options pipeline)

bash scripts/setup.sh
CC=clang CXX=clang++ cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DVGEO_SANITIZE=ON -DVGEO_FUZZ=ON >/dev/null
cmake --build build-asan -j "$(nproc)" >/dev/null

work=build-asan/fuzz
mkdir -p "$work"
cgal=$work/cgal
if [ ! -d "$cgal/data" ]; then
  mkdir -p "$cgal" && tar xzf /usr/share/doc/libcgal-dev/data.tar.gz -C "$cgal" data/meshes data/points_3
fi
assimp=/usr/share/assimp/models/glTF2

# seeds TARGET: prints the seed files of a target, small ones only (the fuzzer mutates, size is no aim).
seeds() {
  case "$1" in
    obj) ls assets/*.obj tests/inputs/*.obj ;;
    off) find "$cgal" tests/inputs -name '*.off' -size -24k ;;
    ply) find "$cgal" tests/inputs -name '*.ply' -size -64k ;;
    gltf) find "$assimp" tests/inputs -name '*.gltf' -size -64k ;;
    glb) find "$assimp" tests/inputs -name '*.glb' -size -64k ;;
    vgeo) ls tests/inputs/*.vgeo "$work"/seed_*.vgeo ;;
    json) ls tests/inputs/*.json "$work"/seed_scene.json ;;
    options) ls "$work"/options_seeds/* ;;
    pipeline) ls "$work"/pipeline_seeds/* ;;
  esac
}
# Seeds that are made: small .vgeo files, a valid scene, and OBJ/OFF cages behind a byte (format, subdiv).
build-asan/vgeo build "$cgal/data/meshes/cube_quad.off" -o "$work/seed_cube.vgeo" -q --subdiv 1 >/dev/null
build-asan/vgeo build "$cgal/data/meshes/tetrahedron.off" -o "$work/seed_tetra.vgeo" -q >/dev/null
echo '{"geometries": ["a.vgeo"], "instances": [{"geometry": 0, "translation": [1, 2, 3], "rotation": [0, 0, 0, 1], "scale": [1, -1, 1]}]}' \
  >"$work/seed_scene.json"
# Option texts behind their parser's byte (fuzz_options.cpp): a size, a camera, a light, a tau, lists, names.
mkdir -p "$work/options_seeds"
i=0
for seed in "\x001920x1080" "\x011,2,3,0,0,0" "\x020.3,1,0.5" "\x031e39" "\x041,4,0.5" "\x05100,10000" "\x06auto" \
  "\x07persistent"; do
  printf "$seed" >"$work/options_seeds/seed_$i"
  i=$((i + 1))
done
mkdir -p "$work/pipeline_seeds"
for f in assets/horned_cube.obj tests/inputs/build_*.obj "$cgal"/data/meshes/{cube_quad,tetrahedron,fold,quad,hole,cube-ouvert}.off; do
  [ "$(stat -c %s "$f")" -lt 4000 ] || continue
  for b in 0 1 2 3 4 5; do
    case "$f" in *.off) byte=$((2 * b + 1)) ;; *) byte=$((2 * b)) ;; esac
    { printf "\\x$(printf %02x $byte)"; cat "$f"; } >"$work/pipeline_seeds/$(basename "$f").$b"
  done
done

status=0
: >"$work/counts.txt"
for t in "${targets[@]}"; do
  corpus=$work/$t
  mkdir -p "$corpus"
  seedDir=$work/seeds_$t
  rm -rf "$seedDir" && mkdir -p "$seedDir"
  seeds "$t" | while read -r s; do cp "$s" "$seedDir/"; done
  log=$work/$t.log
  echo "fuzz: $t for $what" >&2
  failed=0
  started=$SECONDS
  # Leak checks stay on: the readers must not leak either.
  if ! (cd "$work" && ASAN_OPTIONS=abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1 \
        "../tests/fuzz_$t" "${limit[@]}" -timeout=5 -rss_limit_mb=2048 -print_final_stats=1 \
        "$t" "seeds_$t" >"$t.log" 2>&1); then
    echo "fuzz: $t FAILED (see $log)" >&2
    tail -n 30 "$log" >&2
    # The input itself, so that a run on a machine that is thrown away (CI, a fresh container) keeps it.
    for a in "$work"/crash-* "$work"/timeout-* "$work"/oom-*; do
      if [ -f "$a" ]; then echo "fuzz: $t input $(basename "$a"), base64: $(base64 -w 0 "$a")" >&2; fi
    done
    status=1
    failed=1
  fi
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -n 1)
  echo "$t $runs executions ($what asked) in $((SECONDS - started)) s, corpus $(ls "$corpus" | wc -l) inputs$([ $failed = 0 ] || echo ', FAILED')" | tee -a "$work/counts.txt" >&2
done
exit $status

#!/usr/bin/env bash
# The test suite built with clang under AddressSanitizer and UndefinedBehaviorSanitizer (build-asan/):
# every test that needs no GPU, then a GPU smoke test on lavapipe (the viewer under Xvfb with it), then
# each libFuzzer target for FUZZ_SECONDS (default 60; scripts/fuzz.sh). Any sanitizer report fails the
# run. scripts/test.sh runs it after the normal suite.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
CC=clang CXX=clang++ cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DVGEO_SANITIZE=ON -DVGEO_FUZZ=ON >/dev/null
cmake --build build-asan -j "$(nproc)" >/dev/null
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
# MemoryStaysFlat runs in the normal suite only: ASan's quarantine keeps freed memory resident.
gpu='^(Render|Rasters/RenderPatches|RenderInstances|RenderLargeScenes|RenderOcclusion|BenchCut|BenchFrame|BenchBuild|CommandLine|Viewer)\.|^Normals\.GltfFaceNormals|^HostileValues\.(WhatCheckRefuses|ViewsAndPlaces|SceneFilesAreCounted|MemoryStaysFlat)'
ctest --test-dir build-asan -j "$(nproc)" --output-on-failure -E "$gpu"
# lavapipe's LLVM JIT keeps memory to the end of the process; none of it is the project's, so leak
# checks are off for the tests that draw.
ASAN_OPTIONS=detect_leaks=0 ctest --test-dir build-asan -j "$(nproc)" --output-on-failure \
  -R '^(Rasters/RenderPatches\.ThousandsOfPatchesCoverWhatTheTrianglesCover/.*|Render\.GpuDrawListEqualsCpuCutForAllTraversals|CommandLine\..*|Viewer\..*|BenchBuild\..*|HostileValues\.(WhatCheckRefuses|ViewsAndPlaces|SceneFilesAreCounted).*)$'
bash scripts/fuzz.sh "${FUZZ_SECONDS:-60}"

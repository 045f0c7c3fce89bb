# gpu_env.sh: sourced by the bench/gpu_*.sh scripts, on an NVIDIA machine without the project's packages.
# Beside the checkout: .gl/ (the Vulkan loader .debs), .dev/vgeo (the binary built here), .dev/lib/ (the
# shared libraries `ldd build/vgeo` lists that the machine lacks: libtinygltf, libstb),
# .dev/data/ (armadillo.off, corner_tris_with_hole.off) and the vulkan-validationlayers .deb in .dev/.
# Unpacks the loaders, sets V to the binary and records the GPU and driver in gpu.txt of folder $1
# (default $OUT); `validated COMMAND...` runs a command with the Khronos validation layer found.
for f in .gl/*.deb; do dpkg -x $f /; done
ldconfig
export LD_LIBRARY_PATH=$PWD/.dev/lib
V=.dev/vgeo
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > "${1:-$OUT}/gpu.txt" 2>&1
# The SM clock every 100 ms into clocks.csv while the script runs. An H100 between a benchmark's short
# submissions fell to 345-885 MHz, and one binary measured up to 3.5x slower in one call than in the next
# (docs/gpu-notes.md, 24); with this query running the clock read 1980 MHz through the timed records, and
# the records compare. It only reads (no clock is set).
if [ -z "${VGEO_CLOCK_LOG:-}" ]; then
  nvidia-smi --query-gpu=timestamp,clocks.sm,utilization.gpu --format=csv,noheader -lms 100 > "${1:-$OUT}/clocks.csv" 2>&1 &
  export VGEO_CLOCK_LOG=$!
  trap 'kill $VGEO_CLOCK_LOG 2>/dev/null' EXIT
fi
validated() {
  [ -d /tmp/vl ] || { mkdir -p /tmp/vl && dpkg -x .dev/vulkan-validationlayers_*.deb /tmp/vl; }
  VK_LAYER_PATH=/tmp/vl/usr/share/vulkan/explicit_layer.d LD_LIBRARY_PATH=$LD_LIBRARY_PATH:/tmp/vl/usr/lib/x86_64-linux-gnu "$@"
}

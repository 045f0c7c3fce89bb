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
validated() {
  [ -d /tmp/vl ] || { mkdir -p /tmp/vl && dpkg -x .dev/vulkan-validationlayers_*.deb /tmp/vl; }
  VK_LAYER_PATH=/tmp/vl/usr/share/vulkan/explicit_layer.d LD_LIBRARY_PATH=$LD_LIBRARY_PATH:/tmp/vl/usr/lib/x86_64-linux-gnu "$@"
}

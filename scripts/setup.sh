#!/usr/bin/env bash
# Installs the Debian 12 packages vgeo needs to build, test and render; installs only what is missing.
# Idempotent: a second run with everything present does nothing but check.
set -euo pipefail
packages=(
  cmake g++ make pkg-config git ca-certificates
  libopenmesh-dev libcgal-dev libglm-dev libtinygltf-dev nlohmann-json3-dev libcli11-dev libstb-dev
  libtbb-dev libgtest-dev
  libvulkan-dev glslang-tools mesa-vulkan-drivers vulkan-validationlayers
  libglfw3-dev libimgui-dev xvfb xauth twm
  libcgal-demo assimp-testmodels python3 python3-matplotlib
  clang libclang-rt-14-dev clang-format-14
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}" >&2
  sudo_cmd=""; [ "$(id -u)" -eq 0 ] || sudo_cmd="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $sudo_cmd apt-get update -qq
  $sudo_cmd apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

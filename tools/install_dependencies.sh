#!/usr/bin/env bash
# Installs what vkdiffrender needs to build, run and test on Debian 12 (and clang with
# its libFuzzer runtime for tools/fuzz.sh), all from Debian's packages. Run as root;
# does nothing that is already done.
set -euo pipefail

packages=(
  cmake g++ make pkg-config
  libvulkan-dev libvulkan-volk-dev mesa-vulkan-drivers vulkan-validationlayers glslang-tools
  libtinygltf-dev nlohmann-json3-dev libstb-dev
  libopenexr-dev libglm-dev libtbb-dev libcli11-dev
  libgtest-dev
  clang libclang-rt-14-dev
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi
if [ "$(id -u)" -ne 0 ]; then
  echo "missing packages: ${missing[*]}; run this script as root to install them" >&2
  exit 1
fi
export DEBIAN_FRONTEND=noninteractive
apt-get update -qq
apt-get install -y -qq --no-install-recommends "${missing[@]}"

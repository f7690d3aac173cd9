#!/usr/bin/env bash
# Installs what vkdiffrender needs to build, run and test on Debian 12 (the Python module's
# pybind11, numpy, PyTorch and pytest among them; Blender for the add-on's tests against
# Cycles; clang with its libFuzzer runtime for tools/fuzz.sh) from Debian's packages, then the Khronos glTF
# validator from npm into build/npm for the test that validates the shipped and
# documented scenes. Run as root; does nothing that is already done.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
gltf_validator=gltf-validator@2.0.0-dev.3.10

packages=(
  cmake g++ make pkg-config
  libvulkan-dev libvulkan-volk-dev mesa-vulkan-drivers vulkan-validationlayers glslang-tools spirv-tools
  libtinygltf-dev nlohmann-json3-dev libstb-dev
  libopenexr-dev libglm-dev libtbb-dev libcli11-dev zlib1g-dev
  libopenvdb-dev libnanovdb-dev libopenvdb-tools libboost-iostreams-dev libboost-dev
  libgtest-dev
  pybind11-dev python3-dev python3-numpy python3-torch python3-pytest
  blender
  clang libclang-rt-14-dev
)
# node and npm run the glTF validator; a node from elsewhere (NodeSource) carries its own npm.
command -v node > /dev/null || packages+=(nodejs)
command -v npm > /dev/null || packages+=(npm)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -ne 0 ]; then
  if [ "$(id -u)" -ne 0 ]; then
    echo "missing packages: ${missing[*]}; run this script as root to install them" >&2
    exit 1
  fi
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

# Without the registry the validator test reports itself skipped; everything else runs.
if [ "$(npm ls --prefix "$root/build/npm" --parseable "$gltf_validator" 2>/dev/null)" = "" ]; then
  npm install --prefix "$root/build/npm" --no-audit --no-fund --loglevel=error "$gltf_validator" \
    || echo "warning: could not install $gltf_validator; the glTF validator test will be skipped" >&2
fi

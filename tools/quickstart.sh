#!/usr/bin/env bash
# The main job from a fresh Debian 12 machine: install, build, render the fog Cornell
# box, then recover an absorbing medium's sigma_a from a target image (the thesis's
# Cornell box experiment) and print recovered against true values.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/tools/install_dependencies.sh"
"$root/tools/build.sh"
mkdir -p "$root/out"
"$root/build/src/cli/vkdiffrender" render "$root/scenes/cornell_fog.gltf" \
  --width 256 --height 256 --spp 64 --max-depth 8 \
  -o "$root/out/cornell_fog.exr" --png "$root/out/cornell_fog.png"
echo "The fog Cornell box is in out/cornell_fog.exr (linear EXR) and out/cornell_fog.png (preview)."
"$root/build/src/cli/vkdiffrender" optimize --experiment "$root/scenes/experiments/cornell_absorption.json" \
  --out "$root/out/cornell_absorption" --overwrite

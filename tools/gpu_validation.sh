#!/usr/bin/env bash
# Runs every primal and adjoint stage under GPU-assisted validation, which instruments
# each shader to catch out-of-bounds buffer accesses that lavapipe would otherwise
# hide: the render tests with enclosed media, shadow rays among occluders and the BVH
# traversal, and one small gradient of the smoke box (2 spp, so that its samples split:
# docs/gradients.md). Run it after changing a shader or a buffer layout.
#
# It is not part of .ci/run: lavapipe takes about ten minutes to compile the
# instrumented stages on two cores, which CI's 30 minutes cannot spare. Every test in
# CI runs with the validation layer and synchronization validation on.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/tools/build.sh"
export LP_NUM_THREADS=2
VKDR_VALIDATION=gpu "$root/build/tests/render/vkdr_render_tests" --gtest_brief=1 \
  --gtest_filter='GpuTraversal*:CameraInMedium*:ShadowRay*'
work="$root/build/gpu-assisted-validation"
mkdir -p "$work"
"$root/build/src/cli/vkdiffrender" render "$root/scenes/cornell_smoke.gltf" --width 8 --height 8 --spp 1 \
  --max-depth 3 -o "$work/target.exr"
VKDR_VALIDATION=gpu "$root/build/src/cli/vkdiffrender" grad "$root/scenes/cornell_smoke.gltf" \
  --target "$work/target.exr" --param media/smoke/sigma_s --param materials/white/base_color \
  --set media/smoke/sigma_s=1 --spp 2 --max-depth 3 --json
echo
echo "GPU-assisted validation: no messages"

#!/usr/bin/env bash
# Installs, builds, and runs the whole test suite on lavapipe with the Vulkan
# validation layers on (synchronization validation in every test, and a second run of
# the GPU tests under GPU-assisted validation, which catches out-of-bounds accesses).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/tools/install_dependencies.sh"
"$root/tools/build.sh"
cd "$root/build"
# lavapipe runs compute on the CPU: two worker threads suit a two-core machine.
export LP_NUM_THREADS=2
ctest --output-on-failure --timeout 600
echo "GPU-assisted validation over the renderer tests:"
VKDR_VALIDATION=gpu "$root/build/tests/render/vkdr_render_tests" --gtest_brief=1 \
  --gtest_filter='GpuTraversal*:Determinism*:CameraInMedium*'

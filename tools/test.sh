#!/usr/bin/env bash
# Installs, builds, and runs the whole test suite on lavapipe with the Vulkan
# validation layers on (synchronization validation in every test, and a second run of
# the GPU tests under GPU-assisted validation, which catches out-of-bounds accesses),
# then the suites that need no device under AddressSanitizer and UBSan (tools/sanitize.sh).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/tools/install_dependencies.sh"
"$root/tools/build.sh"
cd "$root/build"
# lavapipe runs compute on the CPU: two worker threads suit a two-core machine.
export LP_NUM_THREADS=2
ctest --output-on-failure --timeout 600
# GPU-assisted validation makes lavapipe orders of magnitude slower: it covers one
# render test with enclosed media, the traversal, and the adjoint pass through `grad`.
echo "GPU-assisted validation over the primal and adjoint stages:"
VKDR_VALIDATION=gpu "$root/build/tests/render/vkdr_render_tests" --gtest_brief=1 \
  --gtest_filter='GpuTraversal*:CameraInMedium*'
VKDR_VALIDATION=gpu "$root/build/tests/cli/vkdr_cli_tests" --gtest_brief=1 --gtest_filter='CliTest.GradPrintsOneJsonObject'
# The benchmark harness runs once on a tiny setting: it must work; its times gate nothing.
"$root/build/src/cli/vkdiffrender" bench cornell_fog room_10k --width 32 --spp 1 --iters 1 \
  --json "$root/build/bench-smoke.json"
echo "AddressSanitizer and UndefinedBehaviorSanitizer over the suites that need no device:"
"$root/tools/sanitize.sh"

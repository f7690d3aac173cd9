#!/usr/bin/env bash
# Installs, builds, and runs the whole test suite on lavapipe with the Vulkan
# validation layer and synchronization validation on in every test, then the suites
# that need no device under AddressSanitizer and UBSan (tools/sanitize.sh).
# GPU-assisted validation of the shaders takes longer than CI can spare on two cores:
# tools/gpu_validation.sh runs it.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/tools/install_dependencies.sh"
"$root/tools/build.sh"
cd "$root/build"
# lavapipe runs compute on the CPU with two worker threads per process. Tests run one
# per core at a time all the same: many suites spend part of their time on one thread
# (loading, building BVHs, compiling pipelines), and no test depends on its timing.
export LP_NUM_THREADS=2
ctest --output-on-failure --timeout 600 -j "$(nproc)"
# The benchmark harness runs once on a tiny setting: it must work; its times gate nothing.
"$root/build/src/cli/vkdiffrender" bench cornell_fog room_10k --width 32 --spp 2 --iters 1 \
  --json "$root/build/bench-smoke.json"
echo "AddressSanitizer and UndefinedBehaviorSanitizer over the suites that need no device:"
"$root/tools/sanitize.sh"

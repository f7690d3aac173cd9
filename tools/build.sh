#!/usr/bin/env bash
# Configures and builds vkdiffrender (and its tests) into build/.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
# -O2 with line tables and function names (-g1): stack traces and profilers need no
# more, and full debug information (-g) makes the build about a third slower.
cmake -S "$root" -B "$root/build" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -g1 -DNDEBUG" -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O2 -g1 -DNDEBUG" \
  > "$root/build-configure.log" \
  || { cat "$root/build-configure.log"; exit 1; }
cmake --build "$root/build" -j "$(nproc)"

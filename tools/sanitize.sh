#!/usr/bin/env bash
# Builds the unit tests that need no Vulkan device (scene loading, BVH, images, the
# optimiser, the shader maths compiled on the host) with AddressSanitizer and
# UndefinedBehaviorSanitizer into build-sanitize/, and runs them; any sanitizer report
# stops the run and fails the script. tinygltf is compiled from its header there, so
# its parser is checked too.
#
# The suites that render on lavapipe are left out: under ASan the Vulkan loader, the
# validation layer and Mesa's CPU driver (none of them instrumented) are slow and report
# leaks and errors of their own that are not ours to fix. Only the needed targets are
# built, to keep CI's time down.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build="$root/build-sanitize"
# g++: clang 14 cannot yet capture structured bindings in lambdas (src/bvh/build.cpp does).
compiler=g++
flags="-fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer"

mkdir -p "$build"
# -O1 -g1, as the sanitizers' documentation suggests: fast enough, readable stack
# traces, and a quicker build than -O2 -g.
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1" \
  -DCMAKE_CXX_COMPILER="$compiler" \
  -DCMAKE_CXX_FLAGS="$flags" -DCMAKE_EXE_LINKER_FLAGS="$flags" -DVKDR_TINYGLTF_FROM_HEADER=ON \
  > "$build/configure.log" || { cat "$build/configure.log"; exit 1; }

tests=(vkdr_scene_tests bvh_build_test closest_hit_test image_test vkdr_optimize_tests vkdr_shader_library_tests)
cmake --build "$build" -j "$(nproc)" --target "${tests[@]}"

export ASAN_OPTIONS=halt_on_error=1:abort_on_error=1:detect_leaks=1:strict_string_checks=1:detect_stack_use_after_return=1
export UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1
for test in "${tests[@]}"; do
  binary=$(find "$build/tests" -type f -name "$test" -perm -u+x | head -n 1)
  echo "sanitized: $test"
  (cd "$(dirname "$binary")" && "$binary" --gtest_brief=1)
done

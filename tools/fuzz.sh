#!/usr/bin/env bash
# Fuzzes the scene loader and the target-image reader with libFuzzer (clang's
# -fsanitize=fuzzer, with AddressSanitizer and UndefinedBehaviorSanitizer):
#   tools/fuzz.sh MINUTES [scene|image]   (both when none is named; 0 minutes only builds)
# Builds into build-fuzz/ (the normal build is not touched) and runs at low priority.
# New inputs go to build-fuzz/corpus/TARGET; the seeds are tests/fuzz/corpus/TARGET, the
# malformed-input corpus and the inputs that once crashed (tests/fuzz/regressions/TARGET).
# An input may take seconds: a hierarchy that instances a mesh 2^20 times (the most the
# loader allows) takes half a second normally and many times that instrumented, hence
# the 60 s timeout. A crash leaves build-fuzz/crash-* (or timeout-*, oom-*): fix it,
# then keep the input in tests/fuzz/regressions/TARGET with the extension the loader
# expects (.gltf, .glb, .exr, .png); the replay tests run it.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
minutes=${1:?usage: tools/fuzz.sh MINUTES [scene|image]}
targets=${2:-scene image}
build="$root/build-fuzz"
command -v clang++ > /dev/null || { echo "tools/fuzz.sh needs clang++ (apt-get install clang)" >&2; exit 1; }
flags="-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer"

mkdir -p "$build"
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ \
  -DCMAKE_CXX_FLAGS="$flags" -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" \
  -DVKDR_TINYGLTF_FROM_HEADER=ON -DVKDR_FUZZ=ON -DVKDR_BUILD_TESTS=OFF > "$build/configure.log" \
  || { cat "$build/configure.log"; exit 1; }

for target in $targets; do
  case "$target" in
    scene | image) ;;
    *) echo "unknown fuzz target '$target'; expected scene or image" >&2; exit 2 ;;
  esac
  nice -n 10 cmake --build "$build" -j "$(nproc)" --target "vkdr_fuzz_$target"
  [ "$minutes" -gt 0 ] || continue
  mkdir -p "$build/corpus/$target" "$root/tests/fuzz/regressions/$target"
  echo "fuzzing $target for $minutes minutes"
  (cd "$build" && nice -n 10 "$build/tests/fuzz/vkdr_fuzz_$target" -max_total_time=$((minutes * 60)) \
    -rss_limit_mb=2048 -timeout=60 -print_final_stats=1 \
    "$build/corpus/$target" "$root/tests/fuzz/corpus/$target" "$root/tests/fuzz/regressions/$target" \
    "$root/tests/cli/data/malformed")
done

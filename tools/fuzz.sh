#!/usr/bin/env bash
# Fuzzes one of rgraph's input readers with libFuzzer and keeps what it finds as regression
# inputs that ctest replays (fuzz_replay.TARGET).
#
# Usage: tools/fuzz.sh TARGET SECONDS
#   TARGET: ies (the LM-63 parser and its evaluation), gltf (glTF/GLB loading), image (HDR and
#           EXR environment reading), pipeline (a Lua pipeline through the sandbox, declarations,
#           generated GLSL and the graph compiler), layout (G-buffer layout analysis, code
#           generation, pack/unpack)
#
# The targets (tests/fuzz/fuzz_TARGET.cpp) are built in build-fuzz by clang 16 (Debian packages
# clang-16 and libclang-rt-16-dev, installed here when missing) with libFuzzer and
# AddressSanitizer + UndefinedBehaviorSanitizer. Debian 12's clang 14 cannot: libstdc++ 12 hides
# std::expected, which every rgraph library uses, from compilers that report concepts older than
# C++20's final ones; clang 16 implements what <expected> needs (P0848) but still reports the
# older value, so the build states it (-D__cpp_concepts=202002L). GCC has no libFuzzer
# instrumentation, and AFL++'s GCC plugin in Debian 12 refuses the updated GCC 12.2 it runs on.
#
# Fuzzing starts from the committed corpus tests/fuzz/corpus/TARGET. Afterwards every crash,
# leak-free timeout or out-of-memory input found is copied into tests/fuzz/crashes/TARGET (fix it
# and keep the file: ctest replays it), and the corpus grows by the new inputs that add coverage
# (libFuzzer's -merge), at most 64 KiB each. Prints the run's figures; exits 1 when it found any.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)
targets="ies gltf image pipeline layout"
if [ $# -ne 2 ] || ! echo " $targets " | grep -q " $1 " || ! [[ "$2" =~ ^[0-9]+$ ]] || [ "$2" -lt 1 ]; then
  echo "usage: tools/fuzz.sh TARGET SECONDS   (TARGET: ${targets// /, }; SECONDS: a whole number >= 1)" >&2
  exit 2
fi
target=$1
seconds=$2

tools/install_packages.sh tools/fuzz.sh clang-16 libclang-rt-16-dev

build=${RG_FUZZ_BUILD:-$root/build-fuzz}  # RG_FUZZ_BUILD: another folder (each configuration its own)
if [ ! -f "$build/build.ninja" ]; then
  echo "tools/fuzz.sh: configuring $build (clang 16, libFuzzer, ASan + UBSan)"
  # vptr is left out: glslang is built without RTTI, so its classes have no typeinfo to check.
  sanitize="-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize=vptr -fno-sanitize-recover=undefined -fno-omit-frame-pointer"
  CC=clang-16 CXX=clang++-16 CFLAGS="$sanitize" CXXFLAGS="$sanitize -Wno-macro-redefined -D__cpp_concepts=202002L" \
    LDFLAGS="-fsanitize=address,undefined -fno-sanitize=vptr" \
    cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DRG_FUZZ_ENGINE=-fsanitize=fuzzer >/dev/null
fi
echo "tools/fuzz.sh: building fuzz_$target"
cmake --build "$build" --target "fuzz_$target" --parallel "$(nproc)" >/dev/null

corpus=$root/tests/fuzz/corpus/$target
# The inputs other tests keep start the corpus too, read where they are (tests/CMakeLists.txt's SEEDS).
case $target in
  ies) seeds="tests/unit/ies tests/hostile/inputs" ;;
  gltf) seeds="tests/hostile/inputs" ;;
  image) seeds="tests/hostile/inputs tests/golden/images/stencil_depth" ;;
  pipeline) seeds="tests/hostile/inputs tests/lua/scripts scripts/pipelines" ;;
  layout) seeds="" ;;
esac
crashes=$root/tests/fuzz/crashes/$target
work=$build/findings/$target
rm -rf "$work"
mkdir -p "$work/queue" "$work/artifacts" "$crashes"
export TMPDIR=$work/tmp && mkdir -p "$TMPDIR"
export ASAN_OPTIONS=detect_leaks=0:abort_on_error=0 UBSAN_OPTIONS=print_stacktrace=1
echo "tools/fuzz.sh: fuzzing $target for $seconds s from $(ls "$corpus" | wc -l) corpus inputs and the seeds in ${seeds:-no other folder}"
# -fork keeps fuzzing past a crash (each one is an artifact), so one run reports them all.
set +e
"$build/tests/fuzz_$target" "$work/queue" "$corpus" $seeds -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
  -max_len=65536 -fork=1 -ignore_crashes=1 -ignore_timeouts=1 -ignore_ooms=1 \
  -artifact_prefix="$work/artifacts/" >"$work/log" 2>&1
status=$?
set -e
# In fork mode libFuzzer exits non-zero when it found something; it failed only if it did not run.
grep -q "INFO: exiting\|Done [0-9]* runs" "$work/log" ||
  { echo "tools/fuzz.sh: the fuzzer failed (exit $status); its log: $work/log" >&2; tail -20 "$work/log" >&2; exit 1; }

found=0
for f in "$work"/artifacts/*; do
  [ -f "$f" ] || continue
  cp "$f" "$crashes/$(basename "$f")"
  found=$((found + 1))
done
# The corpus takes the new inputs that add coverage to what it already covers.
before=$(ls "$corpus" | wc -l)
"$build/tests/fuzz_$target" -merge=1 -max_len=65536 -timeout=10 "$corpus" "$work/queue" >"$work/merge.log" 2>&1 || true
find "$corpus" -type f -size +64k -delete
after=$(ls "$corpus" | wc -l)
runs=$(grep -o '#[0-9]*' "$work/log" | tail -1 | tr -d '#')
cov=$(grep -o 'cov: [0-9]*' "$work/log" | tail -1)
echo "tools/fuzz.sh: $target: ${runs:-?} executions in $seconds s, ${cov:-cov: ?} edges;" \
     "$found crashes/timeouts/OOMs kept in tests/fuzz/crashes/$target; $((after - before)) inputs added to tests/fuzz/corpus/$target ($after)"
[ "$found" -eq 0 ]

#!/usr/bin/env bash
# Installs what is missing, builds, and runs the whole test suite (unit, lua, gpu, golden, hostile).
# Extra arguments go to ctest, e.g. tools/test.sh -L unit
#
#   tools/test.sh --sanitize [ctest arguments]
#       builds into build-sanitize with AddressSanitizer and UndefinedBehaviorSanitizer
#       (RG_SANITIZE) and runs the suite there: any report fails the test that made it.
set -euo pipefail
cd "$(dirname "$0")/.."
build=build
if [ "${1:-}" = --sanitize ]; then
  shift
  build=build-sanitize
  export RG_SANITIZE=ON
  # Leaks are not checked: the Vulkan loader, Mesa and the validation layer keep allocations to
  # the end of the process by design. Everything else (out-of-bounds, use after free, undefined
  # behaviour) stops the test with a report.
  export ASAN_OPTIONS=detect_leaks=0:abort_on_error=1:strict_string_checks=1
  export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
fi
tools/setup.sh "$build"
# Every validated device of the suite (GPU tests, and rgraph runs with RG_VALIDATION=1) appends its
# validation-message count here; the total is printed at the end, and any message fails the run.
export RG_VALIDATION_LOG="$PWD/$build/validation.log"
rm -f "$RG_VALIDATION_LOG"
status=0
ctest --test-dir "$build" --output-on-failure -j "$(nproc)" "$@" || status=$?
devices=0 messages=0
if [ -f "$RG_VALIDATION_LOG" ]; then
  devices=$(grep -c '^messages ' "$RG_VALIDATION_LOG" || true)
  messages=$(awk '/^messages /{n += $2} END {print n + 0}' "$RG_VALIDATION_LOG")
fi
echo "validation layer: $messages messages from $devices validated Vulkan devices"
[ "$messages" -eq 0 ] || status=1

# The sanitizer subset every run (CI included) takes: the parsers and the graph compiler — the
# compiler, image, layout, lighting and photometry unit tests and the replay of the IES, EXR/HDR
# and layout fuzz corpora and crashes — built with AddressSanitizer and UndefinedBehaviorSanitizer
# in build-sanitize-core (a few minutes; the whole suite under them, --sanitize, takes ~30).
if [ "$build" = build ]; then
  sub=build-sanitize-core
  echo "tools/test.sh: the parsers and the compiler under ASan + UBSan ($sub)"
  cmake -S . -B "$sub" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DRG_SANITIZE=ON >/dev/null
  units="test_compiler test_image_io test_layout test_lighting test_photometry"
  fuzzers="ies image layout"
  cmake --build "$sub" --parallel "$(nproc)" --target $units $(for f in $fuzzers; do echo "fuzz_$f"; done) >/dev/null
  export ASAN_OPTIONS=detect_leaks=0:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
  for t in $units; do
    (cd "$sub/tests" && "./$t" --gtest_brief=1 >"$t.log" 2>&1) && echo "  $t: passed" || { echo "  $t: FAILED ($sub/tests/$t.log)"; status=1; }
  done
  for f in $fuzzers; do
    # fuzz_replay.$f as ctest runs it (the corpus, the crashes and the seed folders).
    replay=$(ctest --test-dir "$build" -N -V -R "^fuzz_replay\.$f\$" | sed -n 's/^.*Test command: [^ ]* //p' | tr -d '"')
    if out=$("$sub/tests/fuzz_$f" $replay 2>&1); then echo "  fuzz_replay.$f: ${out##*$'\n'}"
    else echo "$out" | tail -20; echo "  fuzz_replay.$f: FAILED"; status=1; fi
  done
fi
exit $status

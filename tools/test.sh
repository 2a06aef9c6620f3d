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
exit $status

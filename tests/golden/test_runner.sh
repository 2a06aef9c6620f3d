#!/usr/bin/env bash
# The golden runner from the command line: test_runner.sh CASE RGRAPH_GOLDEN SOURCE_ROOT TMP
#   must_fail  the perturbed test in tests/golden/must_fail fails (exit 1), names 'hdr' (pass
#              'lighting') as the first divergent resource, passes the G-buffer captures, writes
#              actual / expected / diff images, an HTML report and JUnit XML;
#   update     --update blesses new goldens (and golden.json), a second run passes, a second
#              --update reports them unchanged; a changed test fails, --update rewrites and says
#              what changed, and removes a golden no capture names;
#   usage      no match, a broken test script and a bad option exit 2 with their message;
#   shards     --shard K/N for K = 1..3: every test of the suite runs in exactly one shard.
set -uo pipefail
case_name=$1 bin=$2 root=$3 tmp=$4/$1
rm -rf "$tmp" && mkdir -p "$tmp"
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
expect_rc() { [ "$1" = "$2" ] || fail "$3: exit code $1, expected $2"; }
expect_in() { grep -qF -- "$2" "$1" || fail "'$2' not in $1"; }
expect_not_in() { ! grep -qF -- "$2" "$1" || fail "'$2' unexpectedly in $1"; }
expect_file() { [ -s "$1" ] || fail "missing $1"; }

case $case_name in
must_fail)
  "$bin" --dir "$root/tests/golden/must_fail" --out "$tmp/out" --report "$tmp/report" --junit "$tmp/junit.xml" >"$tmp/log" 2>&1
  rc=$?
  cat "$tmp/log"
  expect_rc $rc 1 "the perturbed test"
  expect_in "$tmp/log" "FAIL  shading_brighter_sun"
  expect_in "$tmp/log" "first divergent resource in pipeline order: 'hdr' (written by 'lighting'): rel_mean"
  expect_in "$tmp/log" "FAIL  <- first divergent"
  for ok in material normal albedo; do
    grep -E "^ +$ok +.* ok$" "$tmp/log" >/dev/null || fail "$ok should still match its golden"
  done
  grep -E "^ +ldr +flip .* FAIL$" "$tmp/log" >/dev/null || fail "ldr should fail after hdr"
  d=$tmp/out/shading_brighter_sun
  for f in hdr.actual.exr hdr.actual.png hdr.expected.exr hdr.expected.png hdr.rel_mean.diff.png hdr.rel_max.diff.png \
           ldr.actual.png ldr.expected.png ldr.flip.diff.png ldr.over_threshold.diff.png; do
    expect_file "$d/$f"
  done
  [ ! -e "$d/normal.actual.exr" ] || fail "a capture that matches writes no artefacts"
  expect_file "$tmp/report/index.html"
  expect_in "$tmp/report/index.html" "first divergent resource in pipeline order"
  expect_in "$tmp/report/index.html" "class=\"swipebox\""
  expect_in "$tmp/junit.xml" 'failures="1"'
  expect_in "$tmp/junit.xml" "<failure message=\"first divergent resource in pipeline order: &apos;hdr&apos;"
  ;;
update)
  mkdir -p "$tmp/tests"
  sed 's/scale = 0.5/scale = 0.25/' "$root/tests/golden/test_pipeline.lua" >"$tmp/tests/blessed.lua"
  run() { "$bin" --dir "$tmp/tests" --images "$tmp/images" --out "$tmp/out" "$@" >"$tmp/log" 2>&1; rc=$?; cat "$tmp/log"; }
  run
  expect_rc $rc 1 "no goldens yet"
  expect_in "$tmp/log" "no golden image"
  expect_in "$tmp/log" "bless it with 'rgraph test blessed --update'"
  run --update
  expect_rc $rc 0 "--update"
  expect_in "$tmp/log" "update: pattern: new golden"
  expect_in "$tmp/log" "update: output: new golden"
  expect_file "$tmp/images/blessed/pattern.exr"
  expect_file "$tmp/images/blessed/output.exr"
  expect_in "$tmp/images/blessed/golden.json" '"mesa"'
  expect_in "$tmp/images/blessed/golden.json" '"lp_num_threads": "2"'
  run
  expect_rc $rc 0 "after blessing"
  expect_in "$tmp/log" "PASS  blessed"
  run --update
  expect_rc $rc 0 "--update again"
  expect_in "$tmp/log" "update: output: unchanged"
  sed -i 's/scale = 0.25/scale = 0.75/' "$tmp/tests/blessed.lua"
  touch "$tmp/images/blessed/stale.exr"
  run
  expect_rc $rc 1 "a changed test"
  expect_in "$tmp/log" "first divergent resource in pipeline order: 'output' (written by 'transform'): max_abs"
  run --update
  expect_rc $rc 0 "--update after the change"
  expect_in "$tmp/log" "update: pattern: unchanged"
  expect_in "$tmp/log" "update: output: updated"
  expect_in "$tmp/log" "(was: max_abs"
  expect_in "$tmp/log" "update: removed"
  [ ! -e "$tmp/images/blessed/stale.exr" ] || fail "stale.exr was not removed"
  run
  expect_rc $rc 0 "after the second blessing"
  ;;
usage)
  "$bin" no_such_test >"$tmp/log" 2>&1
  expect_rc $? 2 "no match"
  expect_in "$tmp/log" "rgraph test: error: no golden test matches 'no_such_test' in tests/golden (tests: "
  mkdir -p "$tmp/tests"
  printf 'return { pipeline = "scripts/pipelines/test.lua", size = { 8, 8 }, captures = { output = { metric = "psnr" } } }\n' \
    >"$tmp/tests/broken.lua"
  "$bin" --dir "$tmp/tests" --images "$tmp/images" --out "$tmp/out" >"$tmp/log" 2>&1
  expect_rc $? 2 "a broken test script"
  expect_in "$tmp/log" "ERROR broken"
  expect_in "$tmp/log" "broken.lua: captures.output.tolerance: missing: metric 'psnr' needs one"
  printf 'return { pipeline = "scripts/pipelines/test.lua", size = { 8, 8 }, captures = { outptu = { metric = "exact" } } }\n' \
    >"$tmp/tests/broken.lua"
  "$bin" --dir "$tmp/tests" --images "$tmp/images" --out "$tmp/out" >"$tmp/log" 2>&1
  expect_rc $? 2 "an unknown capture"
  expect_in "$tmp/log" "captures.outptu: the pipeline has no resource named 'outptu' (did you mean 'output'?)"
  "$bin" --frobnicate >"$tmp/log" 2>&1
  expect_rc $? 2 "an unknown option"
  expect_in "$tmp/log" "rgraph test: unknown option --frobnicate (see 'rgraph test --help')"
  "$bin" --shard 4/3 >"$tmp/log" 2>&1
  expect_rc $? 2 "a shard out of range"
  expect_in "$tmp/log" "rgraph test: --shard must be K/N with 1 <= K <= N, got '4/3' (see 'rgraph test --help')"
  "$bin" --help >"$tmp/log" 2>&1
  expect_rc $? 0 "--help"
  expect_in "$tmp/log" "usage: rgraph test [PATTERN] [--update] [--report DIR] [--junit FILE]"
  ;;
shards)
  # Three shards of the project's golden suite: each test runs in exactly one, and the three
  # JUnit files together hold every test once.
  all=$(ls "$root/tests/golden/"*.lua | xargs -n1 basename | sed 's/\.lua$//' | sort)
  for k in 1 2 3; do
    "$bin" --shard "$k/3" --out "$tmp/out" --junit "$tmp/junit$k.xml" >"$tmp/log$k" 2>&1
    expect_rc $? 0 "shard $k/3"
    expect_in "$tmp/log$k" "rgraph test: shard $k/3: "
  done
  ran=$(cat "$tmp"/junit*.xml | grep -o '<testcase [^>]*name="[^"]*"' | sed 's/.*name="//; s/"$//' | sort)
  [ "$ran" = "$all" ] || fail "the shards ran: $(echo $ran) — expected each of: $(echo $all)"
  ;;
*)
  echo "unknown case $case_name"; exit 2 ;;
esac
if [ $failures -gt 0 ]; then echo "$failures check(s) failed"; exit 1; fi
echo "all checks passed"

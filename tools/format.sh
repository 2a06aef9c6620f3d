#!/usr/bin/env bash
# The house's C++ layout (.clang-format: 100 columns): `tools/format.sh` rewrites every C++ file of
# the project in place; `tools/format.sh --check` changes nothing and fails naming the files that
# are not formatted (the `format` test).
set -euo pipefail
cd "$(dirname "$0")/.."
command -v clang-format > /dev/null || { echo "format: clang-format is not installed (tools/setup.sh installs it)"; exit 2; }
mapfile -t files < <(git ls-files -- 'graph/**.cpp' 'graph/**.h' 'passes/**.cpp' 'passes/**.h' 'include/**.h' \
                                     'tests/**.cpp' 'tests/**.h' 'tools/**.cpp' 'tools/**.h' 'examples/**.cpp' 'examples/**.h')
if [ "${1:-}" = "--check" ]; then
    bad=()
    for f in "${files[@]}"; do
        clang-format --style=file --dry-run --Werror "$f" > /dev/null 2>&1 || bad+=("$f")
    done
    if [ "${#bad[@]}" -gt 0 ]; then
        printf 'format: not formatted (run tools/format.sh): %s\n' "${bad[@]}"
        exit 1
    fi
    echo "format: ${#files[@]} files formatted"
else
    clang-format --style=file -i "${files[@]}"
    echo "format: formatted ${#files[@]} files"
fi

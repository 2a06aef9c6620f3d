#!/bin/sh
# The toon example package (materials/examples/toon) as a game team uses it: copied to a folder
# outside the repository and rendered through its own pipeline.lua and scene.lua, then compared
# with the golden image blessed from a render that was looked at (tests/golden/images/toon_package).
# With --update, writes that golden image instead.
# usage: toon_package.sh RGRAPH SOURCE_ROOT [--update]
set -eu
rgraph=$1
root=$2
golden="$root/tests/golden/images/toon_package/hdr.exr"
tmp=$(mktemp -d "${TMPDIR:-/tmp}/rgraph_toon_package.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
cp -r "$root/materials/examples/toon/." "$tmp/"
cd "$tmp"
RG_VALIDATION=1 "$rgraph" render --pipeline "$tmp/pipeline.lua" --scene "$tmp/scene.lua" --size 192x108 --frames 1 \
    --set dither=false --out "$tmp/toon.exr"
if [ "${3:-}" = "--update" ]; then
    mkdir -p "$(dirname "$golden")"
    cp "$tmp/toon.exr" "$golden"
    cp "$tmp/toon.png" "$(dirname "$golden")/display.png"
    echo "updated $golden"
    exit 0
fi
# Tolerance: the golden suite's HDR bound for other host CPUs (rel_mean 1e-5) with room for the
# half-float EXR round trip.
"$rgraph" compare "$tmp/toon.exr" "$golden" --tolerance 1e-4

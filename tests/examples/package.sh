#!/bin/sh
# An example package (materials/examples/NAME: toon, skin, or all, every package at once) as a
# game team uses it: copied to a folder outside the repository and rendered through its own
# pipeline.lua and scene.lua, then compared with the golden image blessed from a render that was
# looked at (tests/golden/images/NAME_package). With --update, writes that golden image instead.
# usage: package.sh RGRAPH SOURCE_ROOT NAME [--update]
set -eu
rgraph=$1
root=$2
name=$3
golden="$root/tests/golden/images/${name}_package/hdr.exr"
tmp=$(mktemp -d "${TMPDIR:-/tmp}/rgraph_${name}_package.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
cp -r "$root/materials/examples/$name/." "$tmp/"
cd "$tmp"
RG_VALIDATION=1 "$rgraph" render --pipeline "$tmp/pipeline.lua" --scene "$tmp/scene.lua" --size 192x108 --frames 1 \
    --set dither=false --out "$tmp/$name.exr"
if [ "${4:-}" = "--update" ]; then
    mkdir -p "$(dirname "$golden")"
    cp "$tmp/$name.exr" "$golden"
    cp "$tmp/$name.png" "$(dirname "$golden")/display.png"
    echo "updated $golden"
    exit 0
fi
# Tolerance: the golden suite's HDR bound for other host CPUs (rel_mean 1e-5) with room for the
# half-float EXR round trip.
"$rgraph" compare "$tmp/$name.exr" "$golden" --tolerance 1e-4

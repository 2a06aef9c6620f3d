#!/bin/sh
# rgraph as an installed package: `cmake --install` into a temporary prefix, examples/host
# configured against it (find_package(rgraph CONFIG REQUIRED)), built, and run: it renders two
# frames on the Vulkan device it owns and writes them.
# usage: install_host.sh BUILD_DIR SOURCE_ROOT
set -eu
build=$1
root=$2
tmp=$(mktemp -d "${TMPDIR:-/tmp}/rgraph_install.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
cmake --install "$build" --prefix "$tmp/prefix" > "$tmp/install.log"
for f in bin/rgraph include/rgraph/rgraph.h lib/cmake/rgraph/rgraphConfig.cmake lib/cmake/rgraph/rgraphConfigVersion.cmake \
         share/rgraph/scripts/pipelines/deferred.lua share/rgraph/materials/disney.lua share/rgraph/shaders/lib/brdf.glsl; do
    [ -e "$tmp/prefix/$f" ] || { echo "install_host: $f was not installed"; exit 1; }
done
ls "$tmp/prefix"/lib*/librgraph.so* > /dev/null || ls "$tmp/prefix"/lib/*/librgraph.so* > /dev/null
# The library exports its public interface only (namespace rgraph; hidden visibility and a version
# script keep the internal rg:: modules local) and links neither Embree nor the golden runner.
lib=$(ls "$tmp/prefix"/lib*/librgraph.so.* "$tmp/prefix"/lib/*/librgraph.so.* 2>/dev/null | head -n 1)
internal=$(nm -DC --defined-only "$lib" | grep -c ' rg::' || true)
public=$(nm -DC --defined-only "$lib" | grep -c ' rgraph::' || true)
[ "$internal" -eq 0 ] || { echo "install_host: librgraph exports $internal internal rg:: symbols"; nm -DC --defined-only "$lib" | grep ' rg::' | head -5; exit 1; }
[ "$public" -gt 0 ] || { echo "install_host: librgraph exports no rgraph:: symbol"; exit 1; }
if readelf -d "$lib" | grep -qi 'embree'; then echo "install_host: librgraph links Embree"; exit 1; fi
if nm -C --defined-only "$lib" 2>/dev/null | grep -q 'rg::golden::'; then echo "install_host: librgraph carries the golden runner"; exit 1; fi
echo "install_host: librgraph exports $public rgraph:: symbols and no internal ones"
generator=""
command -v ninja > /dev/null && generator="-G Ninja"
# shellcheck disable=SC2086
cmake -S "$root/examples/host" -B "$tmp/host" $generator -DCMAKE_PREFIX_PATH="$tmp/prefix" > "$tmp/configure.log" || { cat "$tmp/configure.log"; exit 1; }
cmake --build "$tmp/host" > "$tmp/build.log" || { cat "$tmp/build.log"; exit 1; }
mkdir -p "$tmp/out"
# The installed copy finds its scripts in PREFIX/share/rgraph (RG_ROOT unset).
env -u RG_ROOT "$tmp/host/rgraph_host" "$tmp/out"
for f in host_frame0.png host_frame1.png host_frame1.exr; do
    [ -s "$tmp/out/$f" ] || { echo "install_host: $f was not written"; exit 1; }
done
# The installed command line runs from the prefix too.
env -u RG_ROOT "$tmp/prefix/bin/rgraph" render --size 32x18 --out "$tmp/out/cli.exr" | grep -q "wrote $tmp/out/cli.exr"
echo "install_host: installed, built examples/host against it, rendered"

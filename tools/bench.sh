#!/usr/bin/env bash
# The benchmark suite (issue: performance): runs `rgraph bench` and friends on this machine and
# writes OUT/bench.json and OUT/bench.md — figures, never pass/fail.
#
#   tools/bench.sh [--out DIR] [--frames N] [--quick] [--size WxH] [--lights-size WxH] [--nodes N]
#
#   default frame   the default pipeline and scene at 1280x720, N frames (default 10), with floors
#   antialiasing    the default frame again with FXAA (--set antialiasing=fxaa): TAA's passes
#                   (taa, taa_moving, taa_history_keep) against FXAA's (fxaa_edges, fxaa)
#   many lights     scripts/scenes/many_lights.lua at 640x360 with 16 to 65 536 lights: the light
#                   culling passes (froxels, tiles) + lighting_standard, and its ratios to 64 lights
#   levels of detail  scripts/scenes/field.lua (1000 dense spheres) at the default size, with its
#                   levels of detail and with every mesh in full (RG_LOD=0): gbuffer, the sun's
#                   maps and the frame
#   city            scripts/scenes/city.lua with 10 000 nodes at the default size: gbuffer, the
#                   sun's maps, CPU recording and the frame, against the default frame
#   compile         a generated 200-pass pipeline (a chain of compute passes): graph compile time
#   start-up        wall time of `rgraph render --frames 1` of the default scene, cold (empty
#                   caches) and warm (the run after it): process start to the image written, and
#                   for the warm run to its first frame done (its --verbose timings: device, load
#                   and frame, before writing the files)
#   reload          pipeline load when everything is cached (`rgraph bench`'s "pipeline load")
#
# --quick: tiny sizes and 2 frames (what the test suite runs to check the script works).
# --size, --lights-size, --nodes: the frame size (default 1280x720), the many-lights sweep's
# (640x360) and the city's nodes (10000) instead. On a hardware GPU the production-scale targets
# are `--size 1920x1080 --lights-size 1920x1080 --nodes 100000`: the city's ratio to the default
# frame and the 16384 / 64 lights ratio, both in bench.md.
# Uses build/rgraph (tools/setup.sh builds it) unless RGRAPH is set.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
rgraph=${RGRAPH:-$root/build/rgraph}
out=$root/build/bench
frames=10
quick=0
while [ $# -gt 0 ]; do
    case $1 in
        --out) out=$2; shift 2 ;;
        --frames) frames=$2; shift 2 ;;
        --quick) quick=1; shift ;;
        --size) size_arg=$2; shift 2 ;;
        --lights-size) lights_size_arg=$2; shift 2 ;;
        --nodes) nodes_arg=$2; shift 2 ;;
        -h|--help) sed -n '2,/^set -euo/p' "$0" | grep '^#' | sed 's/^# \{0,1\}//'; exit 0 ;;
        *) echo "tools/bench.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
    esac
done
[ -x "$rgraph" ] || { echo "tools/bench.sh: no rgraph at $rgraph (run tools/setup.sh)" >&2; exit 2; }
mkdir -p "$out"
size=1280x720 lights_size=640x360 counts="16 64 256 1024 4096 16384 65536" objects=1000 nodes=10000
if [ $quick = 1 ]; then size=96x64 lights_size=64x48 frames=2 counts="16 64" objects=20 nodes=200; fi
size=${size_arg:-$size} lights_size=${lights_size_arg:-$lights_size} nodes=${nodes_arg:-$nodes}

now_ms() { date +%s%3N; }
step() { echo "tools/bench.sh: $*" >&2; }

step "default frame at $size, $frames frames, with floors"
"$rgraph" bench --size "$size" --frames "$frames" --floors --json "$out/default.json" >"$out/default.txt"

step "antialiasing: the default frame with FXAA at $size"
"$rgraph" bench --size "$size" --frames "$frames" --set antialiasing=fxaa --json "$out/fxaa.json" >"$out/fxaa.txt"

for n in $counts; do
    step "many lights: $n at $lights_size"
    "$rgraph" bench --scene "$root/scripts/scenes/many_lights.lua" --scene-arg lights="$n" --size "$lights_size" \
        --frames "$frames" --json "$out/lights_$n.json" >"$out/lights_$n.txt"
done

for lod in 1 0; do
    step "levels of detail: $objects spheres at $size, RG_LOD=$lod"
    RG_LOD=$lod "$rgraph" bench --scene "$root/scripts/scenes/field.lua" --scene-arg objects="$objects" --size "$size" \
        --frames "$frames" --json "$out/field_lod$lod.json" >"$out/field_lod$lod.txt"
done

step "city: $nodes nodes at $size"
"$rgraph" bench --scene "$root/scripts/scenes/city.lua" --scene-arg nodes="$nodes" --size "$size" \
    --frames "$frames" --json "$out/city.json" >"$out/city.txt"

step "compile: a generated 200-pass pipeline"
{
    echo 'local rg = require "rg"'
    echo 'rg.resource "r0" { format = "rgba8", size = { 8, 8 } }'
    echo 'rg.pass "p0" { kind = "clear", writes = { "r0" }, value = { 0, 0, 0, 1 } }'
    for i in $(seq 1 199); do
        echo "rg.resource \"r$i\" { format = \"rgba8\", size = { 8, 8 } }"
        echo "rg.pass \"p$i\" { kind = \"copy\", reads = { \"r$((i - 1))\" }, writes = { \"r$i\" } }"
    done
    echo 'rg.output "r199"'
} >"$out/passes200.lua"
"$rgraph" bench --pipeline "$out/passes200.lua" --size 8x8 --frames 2 --json "$out/compile.json" >"$out/compile.txt"

step "start-up: cold and warm"
cache=$(mktemp -d)
t0=$(now_ms); RG_CACHE_DIR=$cache MESA_SHADER_CACHE_DIR=$cache/mesa "$rgraph" render --size "$size" --out "$out/startup.exr" >/dev/null; t1=$(now_ms)
RG_CACHE_DIR=$cache MESA_SHADER_CACHE_DIR=$cache/mesa "$rgraph" render --size "$size" --out "$out/startup.exr" --verbose >/dev/null 2>"$out/startup_warm.txt"; t2=$(now_ms)
rm -rf "$cache"
# "timings: device D ms, pipeline and scene load L ms, 1 frame F ms, writing W ms": D + L + F.
first=$(sed -n 's/.*timings: device \([0-9]*\) ms, pipeline and scene load \([0-9]*\) ms, 1 frame \([0-9]*\) ms.*/\1 \2 \3/p' "$out/startup_warm.txt" | awk '{print $1 + $2 + $3}')
echo "{\"coldMs\": $((t1 - t0)), \"warmMs\": $((t2 - t1)), \"warmFirstFrameMs\": ${first:-0}}" >"$out/startup.json"

python3 - "$out" "$counts" "$nodes" <<'EOF'
import json, sys
out, counts = sys.argv[1], [int(c) for c in sys.argv[2].split()]
load = lambda name: json.load(open(f"{out}/{name}"))
default = load("default.json")
fxaa = load("fxaa.json")
lights = {n: load(f"lights_{n}.json") for n in counts}
compile_ = load("compile.json")
field = {lod: load(f"field_lod{lod}.json") for lod in (1, 0)}
city = load("city.json")
def passes(b, *names):
    p = {x["name"]: x["medianMs"] for x in b["passes"]}
    return sum(v for k, v in p.items() if any(k.startswith(n) for n in names))
startup = load("startup.json")
def named(b, *names):
    p = {x["name"]: x["medianMs"] for x in b["passes"]}
    return sum(p[n] for n in names)  # a pass renamed: an error here, not a ratio of nothing
def lighting(b):
    p = {x["name"]: x["medianMs"] for x in b["passes"]}
    return sum(v for k, v in p.items() if k.startswith("light_froxels") or k in ("light_culling", "lighting_standard"))
suite = {
    "device": default["device"],
    "default": {"size": default["size"], "frames": default["frames"], "frameTotalMs": default["frameTotalMs"],
                "floorTotalMs": default.get("floorTotalMs"), "passes": default["passes"], "loadMs": default.get("loadMs"),
                "transientBytesAliased": default["transientBytesAliased"], "transientBytesUnaliased": default["transientBytesUnaliased"]},
    "manyLights": {str(n): {"lightingMs": lighting(lights[n]), "frameMs": lights[n]["frameTotalMs"]["median"]} for n in counts},
    "levelsOfDetail": {("lod" if lod else "full"): {"gbufferMs": passes(field[lod], "gbuffer"),
                                                   "sunMapsMs": passes(field[lod], "shadow_sun"),
                                                   "frameMs": field[lod]["frameTotalMs"]["median"]} for lod in (1, 0)},
    "city": {"nodes": int(sys.argv[3]), "gbufferMs": passes(city, "gbuffer", "camera_"), "sunMapsMs": passes(city, "shadow_sun"),
             "frameMs": city["frameTotalMs"]["median"], "cpuRecordMs": city["cpuRecordMs"]["median"],
             "ratioToDefault": city["frameTotalMs"]["median"] / max(default["frameTotalMs"]["median"], 1e-9)},
    "antialiasing": {"taaMs": named(default, "taa", "taa_moving", "taa_history_keep"),
                     "fxaaMs": named(fxaa, "fxaa_edges", "fxaa")},
    "compile200Ms": compile_["compileMs"],
    "startupMs": startup,
}
for n in (1024, 16384, 65536):
    if n in lights and 64 in lights:
        suite["manyLights"][f"ratio{n}to64"] = lighting(lights[n]) / max(lighting(lights[64]), 1e-9)
suite["antialiasing"]["taaToFxaa"] = suite["antialiasing"]["taaMs"] / max(suite["antialiasing"]["fxaaMs"], 1e-9)
json.dump(suite, open(f"{out}/bench.json", "w"), indent=2)
a, u = default["transientBytesAliased"], default["transientBytesUnaliased"]
md = [f"# rgraph bench: {default['device']}", "",
      f"Default frame, {default['size'][0]}x{default['size'][1]}, median of {default['frames']} frames: "
      f"**{default['frameTotalMs']['median']:.1f} ms** (floor {default.get('floorTotalMs', 0):.1f} ms)", "",
      "| pass | median ms | min ms | floor ms | first ms |", "| --- | ---: | ---: | ---: | ---: |"]
for p in default["passes"]:
    md.append(f"| {p['name']} | {p['medianMs']:.2f} | {p['minMs']:.2f} | {p.get('floorMs', 0):.2f} | {p['firstMs']:.2f} |")
md += ["", "| many lights | light culling + lighting ms | frame ms |", "| --- | ---: | ---: |"]
for n in counts:
    md.append(f"| {n} | {lighting(lights[n]):.2f} | {lights[n]['frameTotalMs']['median']:.2f} |")
for n in (1024, 16384, 65536):
    if f"ratio{n}to64" in suite["manyLights"]:
        md.append(f"\n{n} / 64 lights: {suite['manyLights'][f'ratio{n}to64']:.2f}x")
md += ["", "| field of dense spheres | gbuffer ms | sun's maps ms | frame ms |", "| --- | ---: | ---: | ---: |"]
for lod, label in ((1, "levels of detail"), (0, "full meshes (RG_LOD=0)")):
    d = suite["levelsOfDetail"]["lod" if lod else "full"]
    md.append(f"| {label} | {d['gbufferMs']:.2f} | {d['sunMapsMs']:.2f} | {d['frameMs']:.2f} |")
c = suite["city"]
md += ["", f"City of {c['nodes']} nodes: frame {c['frameMs']:.1f} ms ({c['ratioToDefault']:.2f}x the default frame), "
       f"gbuffer {c['gbufferMs']:.1f} ms, the sun's maps {c['sunMapsMs']:.1f} ms, CPU recording {c['cpuRecordMs']:.1f} ms"]
aa = suite["antialiasing"]
md += ["", f"Antialiasing: TAA (taa, taa_moving, taa_history_keep) {aa['taaMs']:.2f} ms against FXAA "
       f"(fxaa_edges, fxaa) {aa['fxaaMs']:.2f} ms: {aa['taaToFxaa']:.2f}x"]
md += ["", f"200-pass graph compile: {compile_['compileMs']:.3f} ms",
       f"Start-up to the first image written: cold {startup['coldMs']} ms, warm {startup['warmMs']} ms "
       f"(warm, to the first frame done: {startup['warmFirstFrameMs']} ms)",
       f"Pipeline load (warm): {default.get('loadMs', 0):.1f} ms",
       f"Transient memory: {a / 2**20:.1f} MiB aliased, {u / 2**20:.1f} MiB without ({100 * (1 - a / max(u, 1)):.1f} % saved)", ""]
open(f"{out}/bench.md", "w").write("\n".join(md))
print("\n".join(md))
EOF
step "wrote $out/bench.json and $out/bench.md"

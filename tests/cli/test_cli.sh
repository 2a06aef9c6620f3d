#!/usr/bin/env bash
# The rgraph command line as a user meets it: help, exit codes (0 ok, 1 failed check, 2 bad
# usage or input), error texts, the files render/bench write, and watch's reload cycle.
# Usage: test_cli.sh RGRAPH_BINARY SOURCE_ROOT TMP_DIR
set -u
rgraph=$1 root=$2 tmp=$3/cli
rm -rf "$tmp" && mkdir -p "$tmp"
cd "$root"
passed=0 failed=0
check() {  # check NAME EXPECTED_RC [grep PATTERN] -- command...
    local name=$1 want=$2; shift 2
    local pattern=""
    if [ "$1" = grep ]; then pattern=$2; shift 2; fi
    [ "$1" = -- ] && shift
    local out rc
    out=$("$@" 2>&1); rc=$?
    if [ "$rc" != "$want" ]; then
        echo "FAIL $name: exit $rc, expected $want"; echo "$out" | head -20; failed=$((failed+1)); return
    fi
    if [ -n "$pattern" ] && ! grep -qF -- "$pattern" <<<"$out"; then
        echo "FAIL $name: output lacks '$pattern'"; echo "$out" | head -20; failed=$((failed+1)); return
    fi
    echo "ok   $name"; passed=$((passed+1))
}

check "help" 0 grep "usage: rgraph COMMAND" -- "$rgraph" --help
check "no command" 2 grep "commands:" -- "$rgraph"
check "unknown command" 2 grep "unknown command 'rendr'" -- "$rgraph" rendr
for c in devices render graph bench watch export-scene bake compare test; do
    check "$c --help" 0 grep "usage: rgraph $c" -- "$rgraph" $c --help
done
check "devices" 0 grep "*" -- "$rgraph" devices
check "render --verbose timings" 0 grep "rgraph: timings: device" -- "$rgraph" render --pipeline builtin:test --size 16x8 --out "$tmp/v.exr" --verbose
check "bad size" 2 grep "--size must be WIDTHxHEIGHT" -- "$rgraph" render --size 12
check "unknown option" 2 grep "unknown option --sise" -- "$rgraph" render --sise 12x12
check "bad device" 2 grep "--device 7: only" -- "$rgraph" render --device 7 --size 8x8 --out "$tmp/x.exr" --png "$tmp/x.png"
check "missing pipeline" 2 grep "cannot open pipeline script 'nope.lua'" -- "$rgraph" render --pipeline nope.lua
check "bad script" 2 grep "unknown_field.lua:3: passes.tonemap.shadr: unknown field (did you mean 'shader'?)" -- \
    "$rgraph" render --pipeline tests/lua/scripts/unknown_field.lua
check "render --verbose: a second rg.output" 0 grep "output_twice.lua:8: rg.output (display 'second') replaces the one at tests/lua/scripts/output_twice.lua:7 (display 'first', hdr 'linear')" -- \
    "$rgraph" render --pipeline "$root/tests/lua/scripts/output_twice.lua" --size 8x8 --out "$tmp/twice.exr" --verbose
python3 - "$root/tests/fuzz/corpus/gltf/triangle.gltf" "$tmp/coat.gltf" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
j["materials"][0]["extensions"] = {"KHR_materials_specular": {"specularFactor": 1, "specularTexture": {"index": 0}}}
j["extensionsUsed"] = ["KHR_materials_specular", "KHR_materials_iridescence"]
json.dump(j, open(sys.argv[2], "w"))
PY
check "render --verbose: what a glTF loses" 0 grep "KHR_materials_specular's textures are ignored (its factors are kept)" -- \
    "$rgraph" render --scene "$tmp/coat.gltf" --size 8x8 --out "$tmp/coat.exr" --verbose
check "... and an extension it ignores, without --verbose" 0 grep "uses extension 'KHR_materials_iridescence', which rgraph ignores" -- \
    "$rgraph" render --scene "$tmp/coat.gltf" --size 8x8 --out "$tmp/coat.exr"
check "unknown capture" 2 grep "capture 'GB7': the pipeline has no resource named 'GB7'" -- "$rgraph" render --capture GB7 --size 8x8
# A frame whose rg.frame switches off what a kept pass needs: refused whole (the frame renders the
# plan as it was), and render stops with exit 2 naming the frame, the switch and the reader.
cat > "$tmp/switch_off.lua" <<'EOF'
require "pipelines.deferred"
local rg = require "rg"
local loopFrame = rg.frame
function rg.frame(ctx)
  if loopFrame then loopFrame(ctx) end
  if ctx.frame >= 1 then ctx.pass("tonemap").enabled = false end
end
EOF
check "rg.frame switching off a needed pass" 2 grep "frame 1: rg.frame's changes (disabled 'tonemap') cannot be built; the plan stays as it was: " -- \
    "$rgraph" render --pipeline "$tmp/switch_off.lua" --size 16x16 --frames 3 --out "$tmp/s.exr" --png "$tmp/s.png"
check "... with the compiler's reason" 2 grep "pass 'fxaa_edges' reads 'display_ldr', but its only writer 'tonemap' is disabled" -- \
    "$rgraph" render --pipeline "$tmp/switch_off.lua" --set antialiasing=fxaa --size 16x16 --frames 3 --out "$tmp/s.exr" --png "$tmp/s.png"
# A camera cut (ctx.cut()) on the last of four frames: every history starts afresh (TAA's and SSR's
# histories, the exposure, the jitter sequence), so that frame is the first frame of a new run.
cat > "$tmp/cut.lua" <<'EOF'
require "pipelines.deferred"
local rg = require "rg"
local loopFrame = rg.frame
function rg.frame(ctx)
  loopFrame(ctx)
  if ctx.frame == 3 then ctx.cut() end
end
EOF
check "a camera cut starts every history afresh" 0 -- bash -c "'$rgraph' render --pipeline '$tmp/cut.lua' --frames 4 --size 64x36 --set dither=false --set taa_jitter=true --out '$tmp/cut.exr' >/dev/null && '$rgraph' render --frames 1 --size 64x36 --set dither=false --out '$tmp/first.exr' >/dev/null && '$rgraph' compare '$tmp/cut.exr' '$tmp/first.exr' --tolerance 0"
check "... and without it they carry over" 1 -- bash -c "'$rgraph' render --frames 4 --size 64x36 --set dither=false --set taa_jitter=true --out '$tmp/nocut.exr' >/dev/null && '$rgraph' compare '$tmp/nocut.exr' '$tmp/first.exr' --tolerance 0 >/dev/null"
check "unknown scene file type" 2 grep "expected a .lua scene script, a .gltf or a .glb file" -- "$rgraph" render --scene README.md --size 8x8
check "missing scene" 2 grep "nope.gltf" -- "$rgraph" render --scene nope.gltf --size 8x8
check "render" 0 grep "wrote $tmp/r.exr and $tmp/r.png (64x32" -- \
    env RG_VALIDATION=1 "$rgraph" render --size 64x32 --frames 3 --out "$tmp/r.exr" --png "$tmp/r.png" --capture GB0
check "render wrote files" 0 -- test -s "$tmp/r.exr" -a -s "$tmp/r.png"
# The once-per-build passes' outputs: saved by the first render, restored by the second (the same
# image), recorded again with --no-cache.
check "render saves once-per-build outputs" 0 grep "10 recorded, saved to $tmp/cache_once/once/" -- \
    env RG_CACHE_DIR="$tmp/cache_once" "$rgraph" render --size 64x32 --out "$tmp/o1.exr" --verbose
check "render restores them" 0 grep "10 restored from $tmp/cache_once/once/" -- \
    env RG_CACHE_DIR="$tmp/cache_once" RG_VALIDATION=1 "$rgraph" render --size 64x32 --out "$tmp/o2.exr" --verbose
check "restored render is the same image" 0 grep "max relative error  0 " -- "$rgraph" compare "$tmp/o2.exr" "$tmp/o1.exr"
check "render --no-cache records them" 0 -- bash -c "! env RG_CACHE_DIR='$tmp/cache_once' '$rgraph' render --size 64x32 --out '$tmp/o3.exr' --verbose --no-cache 2>&1 | grep -q once-per-build"
# Its header: numbers as typed attributes (name, NUL, type, NUL), the pipeline by its name in the project.
check "render metadata is typed" 0 -- python3 -c "d=open('$tmp/r.exr','rb').read(4096); assert b'rgraph.ev100\0float\0' in d and b'rgraph.frames\0int\0' in d and b'rgraph.camera.aperture\0float\0' in d and b'rgraph.pipeline\0string\0' in d and b'scripts/pipelines/deferred.lua' in d and b'$root' not in d, d[:400]"
# --environment: replaces the scene's distant probe; a published glTF with no light is lit by the sky.
check "environment none" 0 grep "wrote $tmp/e.exr" -- \
    env RG_VALIDATION=1 "$rgraph" render --environment none --size 32x16 --out "$tmp/e.exr" --png "$tmp/e.png"
check "variant on a Lua scene" 2 grep "--variant: applies to a .gltf or .glb scene" -- \
    "$rgraph" render --variant rust --size 8x8 --out "$tmp/v.exr"
check "environment sun mode" 2 grep "--environment-sun: expected auto, light, remove or keep, got 'twice'" -- \
    "$rgraph" render --environment-sun twice --size 8x8 --out "$tmp/s.exr"
check "environment missing file" 2 grep "--environment: cannot open 'nowhere.hdr'" -- "$rgraph" render --environment nowhere.hdr --size 8x8
# Baked GI: rgraph bake's progress, figures, cache (by content hash) and EXR (a layer per lobe).
lm=(--scene scripts/scenes/cornell.lua --scene-arg samples=16 --scene-arg density=8)
check "bake" 0 grep "rgraph: baked " -- env RG_CACHE_DIR="$tmp/cache" "$rgraph" bake "${lm[@]}" --out "$tmp/lm.exr"
check "bake progress" 0 grep "rgraph: baking 100 %" -- env RG_CACHE_DIR="$tmp/cache" "$rgraph" bake "${lm[@]}" --rebake
check "bake cached" 0 grep "up to date in the cache" -- env RG_CACHE_DIR="$tmp/cache" "$rgraph" bake "${lm[@]}"
check "bake rebakes a changed scene" 0 grep "rgraph: baked " -- env RG_CACHE_DIR="$tmp/cache" "$rgraph" bake "${lm[@]}" --scene-arg light=dynamic
check "bake EXR layers" 0 -- python3 -c "d=open('$tmp/lm.exr','rb').read(8192); assert b'sg0.R' in d and b'sg8.B' in d and b'rgraph.lightmap.axes' in d and b'rgraph.lightmap.sharpness' in d, d[:300]"
# Sharded bakes (tools/farm.py): the part's figures and cache, and what is refused.
check "bake shard" 0 grep "rgraph: baked shard 2/3: " -- env RG_CACHE_DIR="$tmp/cache" "$rgraph" bake "${lm[@]}" --shard 2/3 --out "$tmp/part2.exr"
check "bake shard cached" 0 grep "rgraph: shard 2/3 (" -- env RG_CACHE_DIR="$tmp/cache" "$rgraph" bake "${lm[@]}" --shard 2/3
check "bake shard out of range" 2 grep "--shard must be K/N with 1 <= K <= N, got '4/3'" -- "$rgraph" bake "${lm[@]}" --shard 4/3
check "bake merge of one shard" 2 grep "lack shard 1/3, 3/3 (given 1 of 3): a merge never writes a partial lightmap" -- \
    env RG_CACHE_DIR="$tmp/cache" "$rgraph" bake --merge "$tmp/part2.exr" --out "$tmp/never.exr"
check "bake merge of a whole lightmap" 2 grep "lm.exr: not an rgraph lightmap: not a shard of a sharded bake" -- "$rgraph" bake --merge "$tmp/lm.exr"
check "bake merge with a scene" 2 grep "--merge takes parts, not --scene" -- "$rgraph" bake --merge "$tmp/part2.exr" --scene x.lua
check "render frame range backwards" 2 grep "render: --frames A..B needs whole numbers 0 <= A <= B, got '3..1'" -- "$rgraph" render --frames 3..1 --size 8x8
check "render warm-up before frame 0" 2 grep "render: --warmup 4 reaches before frame 0" -- "$rgraph" render --frames 2..3 --warmup 4 --size 8x8
check "render frame range" 0 grep "wrote frames 2..3: $tmp/seq/f.0002.exr .. $tmp/seq/f.0003.exr and PNGs (16x8, 2 written, 1 warm-up" -- \
    "$rgraph" render --frames 2..3 --warmup 1 --size 16x8 --out "$tmp/seq/f.####.exr"
check "bake without a lightmap" 2 grep "declares no scene.lightmap" -- "$rgraph" bake --scene scripts/scenes/furnace.lua
check "lightmap view of a lobe it lacks" 2 grep "the lightmap has lobes sg0 .. sg8" -- \
    env RG_CACHE_DIR="$tmp/cache" "$rgraph" render "${lm[@]}" --view sg9 --size 8x8 --out "$tmp/v.exr"
check "lightmap view without a lightmap" 2 grep "--view lightmap: the scene has no baked lightmap" -- "$rgraph" render --view lightmap --size 8x8 --out "$tmp/v.exr"
check "environment wrong type" 2 grep "expected an equirectangular .hdr or .exr file, 'sky' or 'none', got 'sky.png'" -- \
    "$rgraph" render --environment sky.png --size 8x8
cat >"$tmp/unlit.lua" <<'LUA'
local scene = require "scene"
scene.material "white" { base_color = { 0.8, 0.8, 0.8 } }
scene.box "box" { size = { 1, 1, 1 }, material = "white" }
scene.camera "main" { position = { 2, 1.5, 3 }, target = { 0, 0, 0 } }
LUA
check "export unlit" 0 -- "$rgraph" export-scene --scene "$tmp/unlit.lua" --out "$tmp/unlit.glb"
check "unlit glb is lit by the sky" 0 grep "wrote $tmp/u.exr" -- \
    env RG_VALIDATION=1 "$rgraph" render --scene "$tmp/unlit.glb" --size 48x32 --frames 4 --out "$tmp/u.exr" --png "$tmp/u.png"
check "unlit glb without environment" 0 grep "wrote $tmp/n.exr" -- \
    "$rgraph" render --scene "$tmp/unlit.glb" --environment none --size 48x32 --out "$tmp/n.exr" --png "$tmp/n.png"
# The box's pixels: lit under the default sky, black with none (relative error of the unlit image against the lit one: 100 %).
check "sky lights the glb" 0 grep "mean relative error 1" -- "$rgraph" compare "$tmp/n.exr" "$tmp/u.exr"
check "graph json parses" 0 -- bash -c "'$rgraph' graph --format json --size 64x64 | python3 -c 'import json,sys; p=json.load(sys.stdin); n=[x[\"name\"] for x in p[\"passes\"]]; assert n[:7]==[\"env_cube\",\"env_mips\",\"env_irradiance\",\"env_hot\",\"env_smooth_mips\",\"env_prefilter\",\"dfg_table\"] and n[7:10]==[\"probe_capture\",\"probe_mips\",\"probe_prefilter\"] and n[10:19]==[\"sun_cascades\",\"sun_cull_clear\",\"sun_cull\",\"shadow_clear0\",\"shadow_clear1\",\"shadow_clear2\",\"local_cull_clear\",\"local_cull\",\"shadow_local\"] and n[19:25]==[\"camera_early_clear\",\"camera_cull_early\",\"gbuffer_early\",\"camera_hiz\",\"camera_cull_clear\",\"camera_cull\"] and n[25:49]==[\"gbuffer\",\"light_froxels_clear\",\"ao_depth\",\"sun_visibility_clear\",\"sun_classify\",\"sun_visibility_half_clear\",\"sun_classify_half\",\"shadow_sun0\",\"sun_mask0\",\"sun_mask_half0\",\"shadow_sun1\",\"sun_mask1\",\"sun_mask_half1\",\"shadow_sun2\",\"sun_mask2\",\"sun_mask_half2\",\"foliage_fixup\",\"gtao\",\"ao_blur\",\"ao_temporal\",\"light_froxels\",\"light_froxels_large\",\"light_froxels_sort\",\"light_culling\"] and n[52:67]==[\"decals\",\"hiz\",\"ssr_mask\",\"ssr\",\"ssr_temporal\",\"reflection_compose\",\"lighting_standard\",\"lighting_clearcoat\",\"lighting_two_colour\",\"lighting_sheen\",\"sky\",\"lines\",\"opaque_copy\",\"opaque_mips\",\"forward\"] and n[-7:]==[\"tonemap\",\"ssr_history_keep\",\"ssr_distance_history_keep\",\"ao_history_keep\",\"taa_history_keep\",\"hdr_history_keep\",\"hdr_history_mips\"], n'"
check "graph materials" 0 grep "  free: 249 of 255" -- "$rgraph" graph --format materials
check "graph materials: identities first" 0 grep "material identities (a pixel's stencil value" -- "$rgraph" graph --format materials
check "graph materials: foliage is a variant" 0 grep "0x11 mask 0xFF  foliage          variant of lit_standard" -- "$rgraph" graph --format materials
check "graph materials of a built-in graph" 2 grep "built-in graphs declare no materials" -- "$rgraph" graph --pipeline builtin:triangle --format materials
check "export-scene" 0 grep "wrote $tmp/materials.glb (6 meshes" -- "$rgraph" export-scene --scene tests/gpu/scenes/materials.lua --out "$tmp/materials.glb"
check "render a glb" 0 grep "wrote $tmp/g.exr" -- "$rgraph" render --scene "$tmp/materials.glb" --size 64x32 --out "$tmp/g.exr" --png "$tmp/g.png"
check "debug view" 0 grep "wrote $tmp/v.exr" -- "$rgraph" render --scene tests/gpu/scenes/materials.lua --view materialid --size 64x32 --out "$tmp/v.exr" --png "$tmp/v.png"
check "motion view" 0 grep "wrote $tmp/mv.exr" -- "$rgraph" render --view motion --scene-arg move=1 --frames 3 --size 32x16 --out "$tmp/mv.exr"
cat >"$tmp/badpath.lua" <<'LUA'
local scene = require "scene"
scene.box "box" { size = { 1, 1, 1 } }
scene.camera "main" { position = { 2, 1, 3 }, target = { 0, 0, 0 }, path = {
    { time = 1, position = { 2, 1, 3 }, target = { 0, 0, 0 } },
    { time = 0.5, position = { 3, 1, 3 }, target = { 0, 0, 0 } },
} }
LUA
check "camera path out of order" 2 grep "badpath.lua:3: scene.camera.main.path[2].time: is 0.5, not after the key before (1)" -- \
    "$rgraph" render --scene "$tmp/badpath.lua" --size 8x8 --out "$tmp/bp.exr"
check "antialiasing choice" 2 grep "parameter 'antialiasing' expects one of 'taa', 'fxaa', 'none', got 'msaa'" -- "$rgraph" render --set antialiasing=msaa --size 8x8 --out "$tmp/aa.exr"
check "unknown view" 2 grep "--view: unknown view 'albedo'" -- "$rgraph" render --view albedo --size 8x8
# Every shipped scene loads and renders through the default pipeline (their material parameters
# are checked by name against the pipeline's materials).
for sc in scripts/scenes/*.lua; do
    n=$(basename "$sc" .lua)
    check "scene $n renders" 0 grep "wrote $tmp/scene_$n.exr" -- "$rgraph" render --scene "$sc" --size 16x8 --out "$tmp/scene_$n.exr"
done
# An explicit --out puts the PNG beside it (never into ./out); other extensions are refused.
check "png beside --out" 0 grep "wrote $tmp/beside.exr and $tmp/beside.png" -- "$rgraph" render --size 16x8 --out "$tmp/beside.exr"
check "--out must be .exr" 2 grep "--out: '$tmp/x.xyz' is not an .exr path" -- "$rgraph" render --size 8x8 --out "$tmp/x.xyz"
check "--png must be .png" 2 grep "--png: '$tmp/x.jpg' is not a .png path" -- "$rgraph" render --size 8x8 --out "$tmp/x.exr" --png "$tmp/x.jpg"
check "view shadow:LIGHT" 0 grep "wrote $tmp/sl.exr" -- env RG_VALIDATION=1 "$rgraph" render --scene tests/gpu/scenes/local_shadow_box.lua \
    --view shadow:lamp --size 96x64 --out "$tmp/sl.exr" --png "$tmp/sl.png"
check "view shadow:LIGHT names the shadowed lights" 2 grep "--view shadow:sun: the scene has no light 'sun' that casts shadows (those that do: 'lamp')" -- \
    "$rgraph" render --scene tests/gpu/scenes/local_shadow_box.lua --view shadow:sun --size 8x8
for v in cascades shadow ssao ssr ssr_confidence; do
    check "view $v" 0 grep "wrote $tmp/$v.exr" -- env RG_VALIDATION=1 "$rgraph" render --view $v --size 64x32 --out "$tmp/$v.exr" --png "$tmp/$v.png"
done
# Switching off the only writer of the output in rg.frame stops at that frame, naming the pass.
cat >"$tmp/switch_output.lua" <<'LUA'
local rg = require "rg"
rg.resource "pattern" { format = "rgba16f" }
rg.resource "final" { format = "rgba16f" }
rg.pass "generate" { kind = "compute", shader = "test/pattern.comp", writes = { "pattern" } }
rg.pass "show" { kind = "fullscreen", shader = "test/transform.frag", reads = { "pattern" }, writes = { "final" } }
rg.output "final"
function rg.frame(ctx)
    if ctx.frame == 1 then ctx.pass("show").enabled = false end
end
LUA
check "switching off the output's only writer" 2 grep "'final' is exported (an output or a capture) but not written: its only writer 'show' is disabled" -- \
    "$rgraph" render --pipeline "$tmp/switch_output.lua" --frames 3 --size 32x16 --out "$tmp/so.exr"
cat >"$tmp/unshadowed.lua" <<'LUA'
local rg = require "rg"
require "disney"
rg.resource "GB0" { format = "rgb10a2" }
rg.resource "GB1" { format = "rgba8_srgb" }
rg.resource "GB2" { format = "rgba8" }
rg.resource "GB3" { format = "rgba16f" }
rg.resource "depth" { format = "d32f_s8" }
rg.pass "gbuffer" { kind = "scene", writes = { "GB0", "GB1", "GB2", "GB3", "depth" } }
rg.output "GB0"
LUA
check "view shadow needs shadows" 2 grep "--view shadow: the pipeline has no 'sun_shadow0' (require \"shadows\")" -- \
    "$rgraph" render --view shadow --pipeline "$tmp/unshadowed.lua" --size 8x8
# Depth of the default pipeline: once crashed llvmpipe (images placed 16 bytes into a memory block).
check "depth capture" 0 grep "wrote $tmp/depth.exr" -- \
    env RG_VALIDATION=1 "$rgraph" render --capture depth --size 64x32 --out "$tmp/depth.exr" --png "$tmp/depth.png"
# Levels of detail: built and written to <cache>/lods/ by the first process, read by the next.
check "lods built" 0 grep "levels of detail: 4 meshes, 12 levels (3 meshes' from the cache)" -- env RG_CACHE_DIR="$tmp/lodcache" "$rgraph" render --scene "$root/scripts/scenes/field.lua" --scene-arg objects=50 --size 32x16 --out "$tmp/f.exr" --verbose
check "lods from the files" 0 grep "levels of detail: 4 meshes, 12 levels (4 meshes' from the cache)" -- env RG_CACHE_DIR="$tmp/lodcache" "$rgraph" render --scene "$root/scripts/scenes/field.lua" --scene-arg objects=50 --size 32x16 --out "$tmp/f.exr" --verbose
check "channel capture" 0 grep "wrote $tmp/c.exr" -- "$rgraph" render --capture gbuffer.normal --size 32x16 --out "$tmp/c.exr" --png "$tmp/c.png"
check "two-colour channel capture" 0 grep "wrote $tmp/tc.exr" -- \
    "$rgraph" render --scene tests/gpu/scenes/materials.lua --capture two_colour.f0 --size 32x16 --out "$tmp/tc.exr" --png "$tmp/tc.png"
check "compare identical" 0 grep "mean relative error 0" -- "$rgraph" compare "$tmp/r.exr" "$tmp/r.exr" --heatmap "$tmp/heat.png"
check "compare differs" 1 grep "above the tolerance" -- "$rgraph" compare "$tmp/g.exr" "$tmp/r.exr" --tolerance 0.001
check "compare missing layer" 2 grep "has no layer 'nope'" -- "$rgraph" compare "$tmp/r.exr" "$tmp/r.exr" --layer nope
# A supersampled reference: box-filtered to the image's size first; a size that is not N times is refused.
check "compare --downsample" 0 grep "mean relative error" -- bash -c "'$rgraph' render --size 32x16 --frames 3 --out '$tmp/half.exr' >/dev/null && '$rgraph' compare '$tmp/half.exr' '$tmp/r.exr' --downsample 2"
check "compare --downsample: not N times" 2 grep "is 64x32, not 2 times 64x32" -- "$rgraph" compare "$tmp/r.exr" "$tmp/r.exr" --downsample 2
check "compare --downsample: not a number" 2 grep "expected a whole number 1..64, got 'x'" -- "$rgraph" compare "$tmp/r.exr" "$tmp/r.exr" --downsample x
mkdir -p "$tmp/no_gltf"
check "gallery: no folder" 2 grep "gallery needs a folder" -- "$rgraph" gallery
check "gallery: not a folder" 2 grep "is not a folder" -- "$rgraph" gallery "$tmp/r.exr"
check "gallery: no glTF" 2 grep "no .gltf or .glb files under" -- "$rgraph" gallery "$tmp/no_gltf"
check "gallery: bad size" 2 grep "--size 'big': expected WxH" -- "$rgraph" gallery "$tmp/no_gltf" --size big
check "graph dot" 0 grep "digraph rgraph" -- "$rgraph" graph --pipeline scripts/pipelines/test.lua
check "scene args" 0 grep "wrote $tmp/ml.exr" -- \
    env RG_VALIDATION=1 "$rgraph" render --scene scripts/scenes/many_lights.lua --scene-arg lights=8 --set exposure_mode=manual \
    --view lights --size 64x32 --out "$tmp/ml.exr" --png "$tmp/ml.png"
check "scene arg out of range" 2 grep "many_lights.lua:12: scene.args.lights: expected 1..65536 lights, got 70000" -- \
    "$rgraph" render --scene scripts/scenes/many_lights.lua --scene-arg lights=70000 --size 8x8
check "set: bad value" 2 grep "parameter 'exposure_mode' expects one of 'auto', 'manual', got 'nope'" -- "$rgraph" render --set exposure_mode=nope --size 8x8
check "set: unknown parameter" 2 grep "the pipeline has no parameter 'nope'" -- "$rgraph" render --set nope=1 --size 8x8
check "set: no value" 2 grep "render: --set takes NAME=VALUE, got 'exposure_mode'" -- "$rgraph" render --set exposure_mode --size 8x8
check "reference mode" 0 grep "rgraph: frame 4/4" -- \
    env RG_VALIDATION=1 "$rgraph" render --pipeline scripts/pipelines/reference.lua --scene tests/gpu/scenes/reference_rect.lua \
    --frames 4 --size 48x32 --out "$tmp/ref.exr" --png "$tmp/ref.png"
check "reference vs real time" 0 grep "mean relative error" -- \
    bash -c "'$rgraph' render --scene tests/gpu/scenes/reference_rect.lua --size 48x32 --out '$tmp/rt.exr' --png '$tmp/rt.png' >/dev/null && '$rgraph' compare '$tmp/rt.exr' '$tmp/ref.exr'"
# The sun in a chrome sphere is far beyond 65504 cd/m²: the EXR switches to 32-bit floats (no inf).
check "luminance beyond half floats" 0 grep "mean relative error 0" -- \
    bash -c "'$rgraph' render --scene tests/gpu/scenes/reference_sun.lua --size 48x32 --out '$tmp/sun.exr' --png '$tmp/sun.png' >/dev/null && '$rgraph' compare '$tmp/sun.exr' '$tmp/sun.exr'"
check "bench" 0 grep "frame total" -- "$rgraph" bench --size 64x64 --frames 3 --json "$tmp/bench.json"
check "bench json" 0 -- python3 -c "import json; b=json.load(open('$tmp/bench.json')); assert len(b['passes'])==61 and b['frameWallMs']['median'] >= 0.9 * b['frameTotalMs']['median'] and b['scene']['draws']>0 and b['frames']==3 and b['scene']['geometryBytes']>0 and b['scene']['environmentBytes']>0"
# Transient aliasing on the default frame at its default size: the sun's cascade maps take turns in
# one range (scripts/shadows.lua), and the heaps are placed for the passes the first frame runs.
check "aliasing saves 40 %" 0 -- bash -c "'$rgraph' bench --size 1280x720 --frames 1 --json '$tmp/memory.json' >/dev/null && python3 -c \"import json; b=json.load(open('$tmp/memory.json')); s=1-b['transientBytesAliased']/b['transientBytesUnaliased']; assert s>=0.40, s\""
# Floors: every pass measured again with shaders that do nothing; the JSON has both.
check "bench floors" 0 grep "floor" -- "$rgraph" bench --size 64x64 --frames 2 --floors --json "$tmp/floors.json"
check "bench floors json" 0 -- python3 -c "import json; b=json.load(open('$tmp/floors.json')); p={x['name']: x for x in b['passes']}; assert all('floorMs' in x and x['floorMs'] >= 0 for x in b['passes']) and b['floorTotalMs'] > 0 and 'gbuffer' in p, b"
# The benchmark suite (tools/bench.sh): runs at tiny sizes and writes well-formed JSON and Markdown.
check "bench suite" 0 -- env RGRAPH="$rgraph" "$root/tools/bench.sh" --quick --nodes 150 --out "$tmp/suite"
check "bench suite json" 0 -- python3 -c "import json; b=json.load(open('$tmp/suite/bench.json')); assert b['compile200Ms'] > 0 and b['startupMs']['warmMs'] > 0 and b['startupMs']['warmFirstFrameMs'] > 0 and len(b['default']['passes']) > 30 and set(b['manyLights']) >= {'16', '64'} and all('floorMs' in p for p in b['default']['passes']) and b['levelsOfDetail']['lod']['frameMs'] > 0 and b['levelsOfDetail']['full']['gbufferMs'] > 0 and b['city']['nodes'] == 150, b.keys()"
check "bench suite markdown" 0 grep "| pass | median ms" -- cat "$tmp/suite/bench.md"

# watch: a valid script, a broken one (reported, old pipeline kept), a fixed one (picked up),
# then an edited shader (only its pass is rebuilt).
cp shaders/test/transform.frag "$tmp/my.frag"
sed 's#test/transform.frag#my.frag#' scripts/pipelines/test.lua >"$tmp/valid.lua"
cp "$tmp/valid.lua" "$tmp/watched.lua"
"$rgraph" watch --pipeline "$tmp/watched.lua" --size 16x16 --interval 100 --max-reloads 3 \
    --out "$tmp/w.exr" --png "$tmp/w.png" >"$tmp/watch.log" 2>&1 &
pid=$!
for _ in $(seq 100); do grep -q "watching" "$tmp/watch.log" && break; sleep 0.1; done
sleep 0.3; echo 'rg.pass "oops" { kind = "fullscreen", reads = { "nothing" } }' >>"$tmp/watched.lua"
for _ in $(seq 100); do grep -q "reload failed" "$tmp/watch.log" && break; sleep 0.1; done
sleep 0.3; cp "$tmp/valid.lua" "$tmp/watched.lua"; echo "-- fixed" >>"$tmp/watched.lua"
for _ in $(seq 100); do grep -q "reloaded and rendered" "$tmp/watch.log" && break; sleep 0.1; done
sleep 0.3; echo "// edited" >>"$tmp/my.frag"
for _ in $(seq 100); do kill -0 $pid 2>/dev/null || break; sleep 0.1; done
if kill -0 $pid 2>/dev/null; then kill $pid; fi
wait $pid; rc=$?
check "watch exits after its reloads" 0 -- test "$rc" = 0
check "watch reports the broken script" 0 grep "watched.lua:17: passes.oops.reads[1]: unknown resource 'nothing'" -- cat "$tmp/watch.log"
check "watch picks up the fix" 0 grep "reloaded and rendered" -- cat "$tmp/watch.log"
check "watch rebuilds only the edited shader's pass" 0 grep "rebuilt 1 pass(es) (transform), reused 1" -- cat "$tmp/watch.log"

echo "$passed passed, $failed failed"
[ "$failed" = 0 ]

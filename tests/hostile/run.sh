#!/usr/bin/env bash
# The hostile-input suite: bad Lua pipelines and scenes, glTF, IES, HDR/EXR files and command
# lines (tests/hostile/inputs/, plus a few binary ones made here). Every case must exit 2 within
# its time bound with an error naming the file (or option) and the problem — no crash, no hang, no
# Vulkan validation message, no output file left behind. Prints how many were tried and passed.
#
#   tests/hostile/run.sh RGRAPH ROOT TMP
set -u
rgraph=$1 root=$2 tmp=$3/hostile
inputs=$root/tests/hostile/inputs
rm -rf "$tmp"
mkdir -p "$tmp"
cp -r "$inputs/." "$tmp/"
cd "$tmp" || exit 1
rm -f /tmp/rgraph_hostile_pwned
export RG_VALIDATION=1
limit=60  # seconds per case (a memory or instruction bomb stops at the sandbox's limits well before)
tried=0 passed=0

# hostile NAME EXPECTED -- ARGS...: rgraph ARGS must exit 2 with EXPECTED in its output.
hostile() {
    local name=$1 expected=$2
    shift 3
    tried=$((tried + 1))
    rm -f out.exr out.png
    local out rc
    out=$(timeout "$limit" "$rgraph" "$@" 2>&1)
    rc=$?
    local why=""
    if [ $rc = 124 ]; then why="did not finish in $limit s"
    elif [ $rc != 2 ]; then why="exit $rc, expected 2"
    elif ! grep -qF -- "$expected" <<<"$out"; then why="the message does not name '$expected'"
    elif grep -qiE "validation (error|warning)|segmentation|core dumped|terminate called|AddressSanitizer|runtime error" <<<"$out"; then why="crash, sanitizer or validation message"
    elif [ -e out.exr ] || [ -e out.png ]; then why="left an output file behind"
    fi
    [ -n "${HOSTILE_VERBOSE:-}" ] && printf "%-45s %s\n" "$name" "$(head -1 <<<"$out" | cut -c1-200)"
    if [ -n "$why" ]; then
        echo "FAIL $name: $why"
        echo "$out" | head -8 | sed 's/^/    /'
    else
        passed=$((passed + 1))
    fi
}

render() { echo render --size 16x16 --out out.exr "$@"; }

# ---- Lua pipelines: each error names the script (and its line where Lua knows it)
hostile "pipeline: syntax error" "p_syntax.lua:3" -- $(render --pipeline p_syntax.lua)
hostile "pipeline: wrong field type" "p_wrong_type.lua:2" -- $(render --pipeline p_wrong_type.lua)
hostile "pipeline: unknown format" "p_unknown_format.lua:2" -- $(render --pipeline p_unknown_format.lua)
hostile "pipeline: cycle" "p_cycle.lua" -- $(render --pipeline p_cycle.lua)
hostile "pipeline: unknown resource" "nope" -- $(render --pipeline p_unknown_resource.lua)
hostile "pipeline: huge size" "p_huge_size.lua:2" -- $(render --pipeline p_huge_size.lua)
hostile "pipeline: deep recursion" "p_deep_recursion.lua" -- $(render --pipeline p_deep_recursion.lua)
hostile "pipeline: string bomb" "p_string_bomb.lua" -- $(render --pipeline p_string_bomb.lua)
hostile "pipeline: memory bomb" "p_memory_bomb.lua" -- $(render --pipeline p_memory_bomb.lua)
hostile "pipeline: infinite loop" "p_infinite_loop.lua" -- $(render --pipeline p_infinite_loop.lua)
hostile "pipeline: require escape" "p_require_escape.lua:1" -- $(render --pipeline p_require_escape.lua)
hostile "pipeline: require missing" "no_such_module" -- $(render --pipeline p_require_missing.lua)
hostile "pipeline: os.execute" "p_os_execute.lua:1" -- $(render --pipeline p_os_execute.lua)
hostile "pipeline: io.open" "p_io_open.lua:1" -- $(render --pipeline p_io_open.lua)
hostile "pipeline: _G metatable trap" "p_metatable.lua" -- $(render --pipeline p_metatable.lua)
hostile "pipeline: unknown pass kind" "fullscren" -- $(render --pipeline p_unknown_kind.lua)
hostile "pipeline: missing shader" "no_such_shader.frag" -- $(render --pipeline p_missing_shader.lua)
hostile "pipeline: GLSL error" "p_bad_shader.frag:3" -- $(render --pipeline p_shader_error.lua)
hostile "pipeline: depth copied to colour" "p_format_mismatch.lua" -- $(render --pipeline p_format_mismatch.lua)
hostile "pipeline: unknown output" "nothing" -- $(render --pipeline p_unknown_output.lua)
hostile "pipeline: duplicate resource" "p_duplicate.lua:3" -- $(render --pipeline p_duplicate.lua)
hostile "pipeline: error with a table" "p_error_table.lua" -- $(render --pipeline p_error_table.lua)
hostile "pipeline: param default out of range" "p_param_range.lua:2" -- $(render --pipeline p_param_range.lua)
hostile "pipeline: rg.frame raises" "boom in frame" -- $(render --pipeline p_frame_error.lua)
hostile "pipeline: rg.frame sets a wrong type" "p_frame_param_type.lua" -- $(render --pipeline p_frame_param_type.lua)
hostile "pipeline: string.rep separator bomb" "p_rep_separator_bomb.lua" -- $(render --pipeline p_rep_separator_bomb.lua)
hostile "pipeline: binary chunk" "p_binary_chunk.lua" -- $(render --pipeline p_binary_chunk.lua)
hostile "pipeline: endless coroutine" "p_coroutine_loop.lua" -- $(render --pipeline p_coroutine_loop.lua)
# ---- the material system: a team's layouts and materials that the generated code cannot serve
hostile "material: integer target" "m_integer_target.lua:3" -- $(render --pipeline m_integer_target.lua)
hostile "material: define collision" "m_name_collision.lua:4" -- $(render --pipeline m_name_collision.lua)
hostile "material: decal channel in GB3" "fourth target" -- $(render --pipeline m_decal_fourth_target.lua)
hostile "material: variant of a variant" "m_variant_of_variant.lua:3" -- $(render --pipeline m_variant_of_variant.lua)
hostile "pipeline: zero layers" "p_zero_layers.lua:2" -- $(render --pipeline p_zero_layers.lua)
hostile "pipeline: pass reads what it writes" "p_read_own_write.lua" -- $(render --pipeline p_read_own_write.lua)
hostile "pipeline: a lines pass that is also forward" "p_lines_forward.lua:8: pass 'strokes': params.lines" -- $(render --pipeline p_lines_forward.lua)

# ---- Lua scenes
hostile "scene: syntax error" "s_syntax.lua" -- $(render --scene s_syntax.lua)
hostile "scene: negative radius" "s_negative_radius.lua:1" -- $(render --scene s_negative_radius.lua)
hostile "scene: unknown material" "s_unknown_material.lua:1" -- $(render --scene s_unknown_material.lua)
hostile "scene: degenerate camera" "s_camera_degenerate.lua:1" -- $(render --scene s_camera_degenerate.lua)
hostile "scene: point light in lux" "s_light_unit.lua:1" -- $(render --scene s_light_unit.lua)
hostile "scene: a billion segments" "s_huge_segments.lua:1" -- $(render --scene s_huge_segments.lua)
hostile "scene: missing environment file" "nope.hdr" -- $(render --scene s_env_missing.lua)
hostile "scene: zero-size decal" "s_decal_zero.lua:1" -- $(render --scene s_decal_zero.lua)
hostile "scene: nine probes" "s_too_many_probes.lua:1" -- $(render --scene s_too_many_probes.lua)
hostile "scene: memory bomb" "s_memory_bomb.lua" -- $(render --scene s_memory_bomb.lua)
hostile "scene: infinite loop" "s_infinite_loop.lua" -- $(render --scene s_infinite_loop.lua)
hostile "scene: missing texture" "nope.png" -- $(render --scene s_texture_missing.lua)
hostile "scene: texture that is not an image" "s_not_a.png" -- $(render --scene s_texture_not_png.lua)
hostile "scene: NaN intensity" "s_nan_intensity.lua:1" -- $(render --scene s_nan_intensity.lua)

# ---- glTF
"$rgraph" export-scene --scene "$root/tests/gpu/scenes/shadow_box.lua" --out valid.glb >/dev/null 2>&1
head -c 100 valid.glb >g_truncated.glb
head -c 2000 valid.glb >g_truncated_chunk.glb
printf 'glTF\2\0\0\0\377\377\377\177' >g_huge_length.glb
hostile "glTF: truncated header" "g_truncated.glb" -- $(render --scene g_truncated.glb)
hostile "glTF: truncated chunk" "g_truncated_chunk.glb" -- $(render --scene g_truncated_chunk.glb)
hostile "glTF: length field of 2 GiB" "g_huge_length.glb" -- $(render --scene g_huge_length.glb)
hostile "glTF: broken JSON" "g_bad_json.gltf" -- $(render --scene g_bad_json.gltf)
hostile "glTF: accessor past its buffer" "g_accessor_overflow.gltf" -- $(render --scene g_accessor_overflow.gltf)
hostile "glTF: index out of range" "g_index_out_of_range.gltf" -- $(render --scene g_index_out_of_range.gltf)
hostile "glTF: missing buffer file" "no_such_buffer.bin" -- $(render --scene g_missing_buffer.gltf)
hostile "glTF: URI escaping its folder" "leaves the glTF file's folder" -- $(render --scene g_escaping_uri.gltf)
hostile "glTF: network URI" "only relative file names and data: URIs" -- $(render --scene g_network_uri.gltf)
hostile "glTF: absolute URI" "leaves the glTF file's folder" -- $(render --scene g_absolute_uri.gltf)
hostile "glTF: accessor count 2^31" "g_huge_count.gltf" -- $(render --scene g_huge_count.gltf)
hostile "glTF: bad base64" "g_bad_base64.gltf" -- $(render --scene g_bad_base64.gltf)
hostile "glTF: primitive without positions" "g_no_position.gltf" -- $(render --scene g_no_position.gltf)
hostile "glTF: extras name an absolute IES path" "is an absolute path" -- $(render --scene g_extras_absolute_ies.gltf)
hostile "glTF: node names a missing mesh" "g_bad_node_mesh.gltf" -- $(render --scene g_bad_node_mesh.gltf)
hostile "glTF: a name that is a number" "nodes[0].name: expected a string, got 42" -- $(render --scene g_wrong_types.gltf)
hostile "glTF: primitives as an object" "meshes[0].primitives: expected a non-empty array" -- $(render --scene g_primitives_object.gltf)

# ---- IES profiles (through a scene light that names each)
for f in i_truncated i_negative i_nan i_no_tilt i_tilt_file_missing i_garbage i_bad_type i_huge_angles i_type_b_range i_2019_truncated; do
    hostile "IES: ${f#i_}" "$f.ies" -- $(render --scene "$f.lua")
done

# ---- HDR/EXR environments
head -c 300 "$root/tests/golden/images/deferred_pipeline/hdr.exr" >e_truncated.exr 2>/dev/null || printf 'v/1\1' >e_truncated.exr
hostile "environment: .hdr of 100000^2 texels, no data" "e_huge.hdr" -- $(render --environment e_huge.hdr)
hostile "environment: truncated .hdr" "e_truncated.hdr" -- $(render --environment e_truncated.hdr)
hostile "environment: .hdr of zero rows" "e_zero.hdr" -- $(render --environment e_zero.hdr)
hostile "environment: garbage .exr" "e_garbage.exr" -- $(render --environment e_garbage.exr)
hostile "environment: truncated .exr" "e_truncated.exr" -- $(render --environment e_truncated.exr)
hostile "environment: missing file" "no_such.exr" -- $(render --environment no_such.exr)

# ---- The command line
hostile "CLI: size 0x0" "--size" -- render --size 0x0 --out out.exr
hostile "CLI: size beyond the device" "100000" -- render --size 100000x100000 --out out.exr
hostile "CLI: negative frames" "--frames" -- render --frames -1 --out out.exr
hostile "CLI: unknown output extension" "x.xyz" -- render --size 16x16 --out x.xyz
hostile "CLI: unknown option" "--foo" -- render --foo
hostile "CLI: missing pipeline" "no_such_pipeline.lua" -- render --pipeline no_such_pipeline.lua --out out.exr
hostile "CLI: unknown parameter" "no_such_param" -- render --size 16x16 --set no_such_param=1 --out out.exr
hostile "CLI: unknown camera" "no_such_camera" -- render --size 16x16 --camera no_such_camera --out out.exr
hostile "CLI: unknown view" "no_such_view" -- render --size 16x16 --view no_such_view --out out.exr
hostile "CLI: unknown command" "frobnicate" -- frobnicate

[ -e /tmp/rgraph_hostile_pwned ] && { echo "FAIL os.execute ran"; passed=$((passed - 1)); }
echo "hostile inputs: $passed of $tried passed"
[ "$passed" = "$tried" ]

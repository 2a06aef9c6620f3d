-- Shadows (seed 002 §4.10.4; DESIGN §10): the sun's cascaded shadow maps, its shadow mask and the
-- local lights' maps.
--
--   local shadows = require "shadows"   -- declares the maps, the cascades, the mask and the passes
--   rg.pass "lighting_x" (shadows.masked { kind = "fullscreen", ... })  -- deferred: reads the mask
--   rg.pass "forward_x" (shadows.lit { kind = "scene", forward = true, ... })  -- reads the maps
--
-- Each frame `sun_cascades` (compute, one invocation: shaders/shadows/sun_cascades.comp) places
-- shadows.cascades cascades over the view up to `shadow_distance` (practical split scheme,
-- stable by texel snapping) and `sun_cull` (compute) writes an indirect draw command per cascade
-- and draw, with no instance for a draw beside the cascade. After the pass named "gbuffer",
-- `sun_classify` writes each pixel's cascade as a depth code, then for each cascade N
-- `shadow_sunN` (the `scene` kind with shadow = true, indirect, view = { N, cascades }) draws the
-- opaque primitives' depth into `sun_shadowN` and `sun_maskN` filters it at once — lib/shadows.glsl's
-- PCSS (blocker search, penumbra from the sun's angular size) at that cascade's pixels — into
-- `sun_visibility`. Each map is dead after its mask pass, so the graph gives the next one its
-- memory. `shadows.masked` makes a deferred lighting pass multiply the sun's light by the mask;
-- `shadows.lit` makes a pass filter the maps at its own pixels (the forward pass). The passes are
-- culled by the graph when nothing reads what they write, and skipped (rg.frame: shadows.frame)
-- when the scene has no sun or `sun_shadows` is off.
--
-- Local lights declared with `shadow = true` in the scene get shadow views each frame their range
-- reaches the view (passes/gpu_scene_lights.cpp: one perspective view for a spot of outer angle ≤ 60°, a
-- cube of six otherwise, each with the casters its frustum meets); `shadow_local` (the `scene`
-- kind, shadow = true, views = "lights") draws them into the layers of `local_shadow`, and the
-- light loop of a `shadows.lit` pass filters them as it does the sun's, with the penumbra of the
-- light's radius. A frame without such views draws nothing.
local rg = require "rg"
local reader = require "gbuffer_reader"  -- the G-buffer decoded by each pixel's material
local lighting = require "lighting"

local shadows = {}

shadows.size = 2048    -- texels per side of each cascade
shadows.cascades = 3   -- 1..4 (3: each costs a draw of every caster)
shadows.local_size = 1024   -- texels per side of each local light's view
shadows.local_views = 6     -- at most this many layers for local lights' views: one cube, or six spots (24 MiB at 1024²)

rg.param "sun_shadows" { type = "boolean", default = true, doc = "the sun casts shadows (false: the map is only cleared)" }
rg.param "shadow_distance" { type = "number", default = 40, min = 1, max = 10000, doc = "metres of view the sun's cascades cover" }
rg.param "shadow_split_lambda" { type = "number", default = 0.8, min = 0, max = 1, doc = "cascade splits: 0 uniform .. 1 logarithmic (practical split scheme)" }
rg.param "shadow_depth_bias" { type = "number", default = 0.02, min = 0, max = 1, doc = "receiver depth bias, metres along the light" }
rg.param "shadow_normal_offset" { type = "number", default = 1.5, min = 0, max = 16, doc = "lookup offset along the normal, in texels of the cascade" }
rg.param "sun_mask" { type = "choice", default = "auto", choices = { "auto", "full", "half" },
    doc = "resolution of the sun's shadow mask: full, half (a quarter of its cost; thin shadows need the pixels), auto (half from 720 rows up)" }
rg.param "shadow_softness" { type = "number", default = 1, min = 0, max = 16, doc = "penumbra width × the sun's physical one (0: hard)" }

rg.buffer "sun_cascades" { size = 4 * 64 + 5 * 16, doc = "the sun's cascades this frame (lib/shadows.glsl's RgCascades)" }
-- One map per cascade, each a texture of its own: `shadow_sunN` draws cascade N's casters into
-- `sun_shadowN` right after the G-buffer, and `sun_maskN` filters it at once for the pixels of
-- cascade N into `sun_visibility` (the sun's shadow mask, r16f: the PCF's k/16 exactly), which the
-- deferred lighting passes read (shadows.masked) instead of the maps. A map is dead once its
-- pixels are filtered, so the graph places the next cascade's in the same memory: 8 MiB live at a
-- time rather than 24 (at 2048², d16), and none of it beside the lighting's targets. A forward pass
-- (shadows.lit) reads every map, which then lives until it.
-- 16-bit depth: the cascades are orthographic, so depth is linear along the light and 1/65535 of a
-- cascade's depth range is a millimetre or two (the receiver bias is 2 cm); half of d32f's memory,
-- the default frame's image within 7/255 of d32f's in 71 of 2.8 M channels.
-- Caster culling per cascade and instance (shaders/shadows/cascade_cull.comp): the casters that
-- share a mesh and cull mode are a batch, drawn into each cascade as one instanced indirect draw
-- per level of detail with the casters whose boxes meet it — batches × levels draws a cascade
-- rather than one per caster. Both buffers are sized by the scene (scene_count): a command per
-- cascade, batch and level; an instance slot per cascade, level and caster.
rg.buffer "sun_shadow_draws" { size = 20, scene_count = "shadow_batches", count_bytes = shadows.cascades * 4 * 20,
    doc = "the sun's shadow draws: an indirect command per cascade, caster batch and level of detail (VkDrawIndexedIndirectCommand)" }
rg.buffer "sun_shadow_instances" { size = 4, scene_count = "shadow_casters", count_bytes = shadows.cascades * 4 * 4,
    doc = "the casters each of sun_shadow_draws' commands draws: a draw index per instance" }
-- Work groups of 64 of the culling pass: each invocation takes every (64 x this)-th draw.
shadows.cull_groups = 256
rg.pass "sun_cascades" {
    kind = "compute", shader = "shadows/sun_cascades.comp", writes = { { "sun_cascades", as = "storage" } }, groups = { 1, 1, 1 },
    defines = { RG_CASCADES = shadows.cascades, RG_SHADOW_SIZE = shadows.size },
}
rg.pass "sun_cull_clear" { kind = "clear", writes = { "sun_shadow_draws" } }
rg.pass "sun_cull" {
    kind = "compute", shader = "shadows/cascade_cull.comp", groups = { shadows.cull_groups, 1, 1 }, defines = { RG_CASCADES = shadows.cascades },
    reads = { { "sun_cascades", as = "storage" } },
    writes = { { "sun_shadow_draws", as = "storage_rw" }, { "sun_shadow_instances", as = "storage" } },
}

-- The cascade code of each pixel (a depth mask for the mask passes' equal test, so that each
-- shades only its own cascade's pixels) and the mask set to lit: sun_classify.frag.
rg.resource "sun_visibility" { format = "r16f", doc = "the sun's visibility at each pixel (0 shadowed .. 1 lit), for the deferred lighting" }
-- d32f: the codes are exact floats, written and tested without a conversion that might round one
-- of the two another way (in d16, (N + 1) / 8 · 65535 is not a whole number).
rg.resource "sun_cascade_mask" { format = "d32f", doc = "each pixel's sun cascade as a depth code: (N + 1) / 8, 1 for none" }
rg.pass "sun_visibility_clear" { kind = "clear", writes = { "sun_visibility" }, value = 1, insert = { after = "gbuffer" } }
rg.pass "sun_classify" {
    kind = "fullscreen", shader = "shadows/sun_classify.frag", reads = { "depth", { "sun_cascades", as = "uniform" } },
    writes = { { "sun_cascade_mask", as = "depth" } }, depth = { compare = "always", value = 1, write = true },
    insert = { after = "gbuffer" },
}
-- The same mask at half resolution (the `sun_mask` parameter; "auto": from 720 rows up): texel h
-- holds the visibility at full-resolution pixel 2h and that pixel's view distance, which the
-- lighting's depth-aware upsample weighs the four texels around a pixel by (lib/upsample.glsl).
-- The PCSS per texel is the mask's cost: ~21 ms for every pixel at 1280×720 on lavapipe, ~6 for a
-- quarter of them, the upsample in the lighting ~3. Below 720 rows a texel grows coarse enough to
-- step over thin shadows (a panel's edge-on shadow breaks into dots at 192×128), so "auto" keeps
-- full resolution there. The lighting reads both masks and takes the smaller: the one not in use
-- stays cleared to lit.
rg.resource "sun_visibility_half" { format = "rg16f", scale = { 0.5, 0.5 },
    doc = "the sun's visibility at half resolution (0 shadowed .. 1 lit) and the view distance (m) it was filtered at" }
rg.resource "sun_cascade_mask_half" { format = "d32f", scale = { 0.5, 0.5 }, doc = "sun_cascade_mask at half resolution" }
-- Lit, at no distance: a texel no mask pass writes (the sky, beyond the shadow distance) weighs
-- next to nothing beside a surface's own texels, and all such upsample to 1.
-- Announced to the AO module (scripts/ao.lua), which copies it into its own half-resolution target
-- when it is loaded after this one, so that the lighting upsamples the two at once.
lighting.sun_visibility_half = "sun_visibility_half"
rg.pass "sun_visibility_half_clear" { kind = "clear", writes = { "sun_visibility_half" }, value = { 1, 0, 0, 0 }, insert = { after = "gbuffer" } }
rg.pass "sun_classify_half" {
    kind = "fullscreen", shader = "shadows/sun_classify.frag", reads = { "depth", { "sun_cascades", as = "uniform" } },
    writes = { { "sun_cascade_mask_half", as = "depth" } }, depth = { compare = "always", value = 1, write = true },
    defines = { RG_SUN_MASK_HALF = true }, insert = { after = "gbuffer" },
}
for i = 0, shadows.cascades - 1 do
    local map = "sun_shadow" .. i
    rg.resource (map) { format = "d16", size = { shadows.size, shadows.size }, doc = "the sun's shadow map of cascade " .. i }
    -- Without a sun the map is only cleared (to "nothing in the way"): shadows.frame switches
    -- between the two writers.
    rg.pass ("shadow_clear" .. i) { kind = "clear", writes = { map }, depth = 1 }
    -- Only the faces towards the sun (cull): for a closed mesh the nearest surface along the light is
    -- one of them anyway, and the faces turned away were half the triangles the rasteriser set up
    -- (shadow_sun 38–44 → 24–27 ms on the default frame; the image differs in a few silhouette pixels,
    -- PSNR 116 dB). sun_cascades.comp's basis (x, y = x × f, depth along f) has no y flip, so a face
    -- counter-clockwise towards the sun lands clockwise in the map. Double-sided materials draw both.
    rg.pass ("shadow_sun" .. i) {
        kind = "scene", shadow = true,
        reads = { { "sun_cascades", as = "storage" }, { "sun_shadow_draws", as = "indirect" }, { "sun_shadow_instances", as = "storage" } },
        writes = { map }, indirect = "sun_shadow_draws", view = { i, shadows.cascades }, depth_bias = { 1.0, 1.5 },
        after = { "shadow_clear" .. i }, cull = "counter_clockwise", insert = { after = "gbuffer" },
    }
    rg.pass ("sun_mask" .. i) {
        kind = "fullscreen", shader = "shadows/sun_mask.frag", defines = { RG_SUN_CASCADE = i },
        reads = reader.reads { "depth", { "sun_cascades", as = "uniform" }, map, { "sun_cascade_mask", as = "depth" } },
        writes = { { "sun_visibility", load = true } }, bind = { sun_shadow = map },
        depth = { compare = "equal", value = (i + 1) / 8 }, insert = { after = "gbuffer" },
    }
    rg.pass ("sun_mask_half" .. i) {
        kind = "fullscreen", shader = "shadows/sun_mask.frag", defines = { RG_SUN_CASCADE = i, RG_SUN_MASK_HALF = true },
        reads = reader.reads { "depth", { "sun_cascades", as = "uniform" }, map, { "sun_cascade_mask_half", as = "depth" } },
        writes = { { "sun_visibility_half", load = true } }, bind = { sun_shadow = map },
        depth = { compare = "equal", value = (i + 1) / 8 }, insert = { after = "gbuffer" },
    }
end

-- Sized by the scene (scene_layers): as many layers as its shadowed local lights can have views, up
-- to shadows.local_views; a scene without any gets one 1×1 layer instead of 24 MiB.
rg.resource "local_shadow" { format = "d32f", size = { shadows.local_size, shadows.local_size }, layers = shadows.local_views,
    scene_layers = "shadow_views", doc = "the local lights' shadow maps, one layer per shadow view" }
-- The faces towards the light only, as the sun's (its views, lookAt and a projection without a y
-- flip, land those faces clockwise too): the default scene with its lamp shadowed (six cube faces)
-- 24.7–25.4 → 14.4–15.5 ms, the image within PSNR 176 dB.
-- Caster culling per view on the GPU (shaders/shadows/local_cull.comp), as the cascades': the casters
-- sharing a mesh and cull mode drawn into each view as one instanced indirect draw per level of
-- detail with those whose boxes meet its frustum, at the camera's level — what the CPU's walk over
-- every view and caster chose (`gpu_shadow_culling` = false: the CPU walks them again). Only for a
-- scene with a light that casts shadows (only_when): the instance slots are 96 bytes a caster.
rg.param "gpu_shadow_culling" { type = "boolean", default = true,
    doc = "the local lights' shadow casters culled per view on the GPU (false: on the CPU)" }
local local_when = { scene = "local_shadows", param = "gpu_shadow_culling" }
rg.buffer "local_shadow_draws" { size = 20, scene_count = "shadow_batches", count_bytes = shadows.local_views * 4 * 20,
    only_when = local_when,
    doc = "the local lights' shadow draws: an indirect command per view, caster batch and level of detail (VkDrawIndexedIndirectCommand)" }
rg.buffer "local_shadow_instances" { size = 4, scene_count = "shadow_casters", count_bytes = shadows.local_views * 4 * 4,
    only_when = local_when, doc = "the casters each of local_shadow_draws' commands draws: a draw index per instance" }
rg.pass "local_cull_clear" { kind = "clear", writes = { "local_shadow_draws" } }
rg.pass "local_cull" {
    kind = "compute", shader = "shadows/local_cull.comp", groups = { shadows.cull_groups, 1, 1 },
    defines = { RG_LOCAL_VIEWS = shadows.local_views },
    writes = { { "local_shadow_draws", as = "storage_rw" }, { "local_shadow_instances", as = "storage" } },
}
rg.pass "shadow_local" {
    kind = "scene", shadow = true, views = "lights", writes = { "local_shadow" }, depth_bias = { 1.0, 1.5 },
    cull = "counter_clockwise", indirect = "local_shadow_draws",
    reads = { { "local_shadow_draws", as = "indirect" }, { "local_shadow_instances", as = "storage" } },
}

-- A lighting pass's declaration, shadowed by the maps themselves (a forward pass: its pixels are
-- not the G-buffer's): reads every cascade's map and the cascades, defines RG_SHADOWS.
function shadows.lit(pass)
    local reads = { { "sun_cascades", as = "uniform" }, "local_shadow" }
    for i = 0, shadows.cascades - 1 do table.insert(reads, "sun_shadow" .. i) end
    lighting.extend(pass, reads, "RG_SHADOWS")
    pass.defines.RG_SUN_CASCADES = shadows.cascades
    return pass
end

-- A deferred lighting pass's declaration, shadowed: reads the sun's visibility the mask passes
-- filtered at its pixels (RG_SUN_MASK) and the local lights' maps, defines RG_SHADOWS.
function shadows.masked(pass)
    lighting.extend(pass, { "sun_visibility", "sun_visibility_half", { "sun_cascades", as = "uniform" }, "local_shadow" }, "RG_SHADOWS")
    pass.defines.RG_SUN_MASK = true
    return pass
end

-- Per frame: no sun in the scene (or sun_shadows off), no shadow draws — the maps are cleared
-- instead, the mask stays lit, and everything reads as lit.
-- The mask at full or half resolution (the `sun_mask` parameter): the other's passes are switched
-- off, and its mask stays cleared.
function shadows.frame(ctx)
    local draw = ctx.params.sun_shadows and (not ctx.scene or ctx.scene.suns > 0)
    local half = ctx.params.sun_mask == "half" or (ctx.params.sun_mask == "auto" and ctx.height >= 720)
    ctx.pass("sun_cull").auto_enabled = draw
    ctx.pass("sun_cull_clear").auto_enabled = draw
    ctx.pass("sun_classify").auto_enabled = draw and not half
    ctx.pass("sun_classify_half").auto_enabled = draw and half
    for i = 0, shadows.cascades - 1 do
        ctx.pass("shadow_sun" .. i).auto_enabled = draw
        ctx.pass("sun_mask" .. i).auto_enabled = draw and not half
        ctx.pass("sun_mask_half" .. i).auto_enabled = draw and half
        ctx.pass("shadow_clear" .. i).auto_enabled = not draw
    end
end

return shadows

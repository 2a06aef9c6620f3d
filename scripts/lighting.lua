-- Light culling for the deferred lighting passes (seed 000 §4; DESIGN §3), clustered then tiled:
--
--   local lighting = require "lighting"   -- declares the light lists and the passes that fill them
--   rg.pass "lighting_x" (lighting.tiled { kind = "fullscreen", shader = ..., reads = { ... }, ... })
--
-- First a froxel grid (shaders/passes/light_froxels.comp): the screen in columns of 32x32 pixels,
-- each cut into 16 slices of view distance; every ranged light goes into the lists of the froxels
-- its range meets (one invocation per light, or a few sharing its columns when there are few: the
-- cost is the lights times the froxels each covers, not froxels times lights; it also writes each
-- light's view-space sphere, `light_spheres`; a light too large for one invocation's share is left
-- to `light_froxels_large`, whose invocations all share it), and the lists are sorted. Then, after
-- the pass named "gbuffer", `light_culling` lists per 4x4-pixel tile the lights of the froxels its
-- surfaces' depths span that reach those surfaces. Small tiles keep each pixel's loop to the lights near it. The lights
-- that reach every pixel (the sun, lights without a range) are the scene's global list, read by
-- every lighting loop before the tile's. `lighting.tiled` makes a lighting pass read the tile lists
-- (the shader's light loop, through lib/light_tiles.glsl, then visits only the tile's lights). A
-- pipeline that never uses `lighting.tiled` loses these passes to the graph's culling, and its
-- shaders loop over all.
local rg = require "rg"

local lighting = {}

-- Pixels per side of the tiles the lighting passes read. Every pixel of a tile loops over the
-- whole list (a pixel out of a light's range still evaluates it: both sides of a branch run on a
-- CPU rasteriser), so the list should hold what reaches the pixel: in the many-lights scene at
-- 640x360 (about four lights a pixel), lighting + culling cost 7.3 ms at 64 lights and 9.8 at
-- 1024 with 8x8 tiles (1.34x: at 1024 the ranges are a quarter as wide, so a tile's footprint
-- adds more lights around them), 7.3-7.9 and 9.2 with 4x4 tiles (~1.21x).
lighting.tile = 4
-- Words per fine tile: the count, then up to 62 indices of ranged lights, 16 bits each (128 B per
-- tile; 7 MiB at 1280x720). A tile reached by more ranged lights than its list holds keeps the
-- lowest indices (the `lights` view shows them).
lighting.tile_words = 32
-- The froxel grid: pixels per side of its columns, slices per column, and words per froxel (two
-- 16-bit light indices each: up to 254 lights; 8 KiB per column, 7.4 MiB at 1280x720). A froxel
-- reached by more lights than that keeps the first that arrived, and the tiles under it are marked
-- (the `lights` view shows them magenta).
lighting.coarse_tile = 32
lighting.froxel_slices = 16
lighting.froxel_words = 128
-- Work groups of 64 of the binning pass (each invocation takes every (64 x this)-th light, or a
-- share of one light's columns when the lights are fewer than the invocations) and of
-- the sort (one froxel per invocation up to 64 x this froxels: 4K's 130 000 at 1024).
lighting.froxel_groups = 256
lighting.sort_groups = 1024
-- Work groups of the pass of large lights (light_froxels_large): its invocations share the
-- columns of the lights the binning left to it (one across a 4K frame: 8 columns each). Few,
-- since most frames leave it none and an idle invocation still costs a pass of its loop's body
-- on lavapipe (256 groups: 0.46 ms a frame; 16: ~0.13).
lighting.froxel_large_groups = 16
-- The most lights a scene may have is rg.limits.max_lights (shaders/lib/limits.h's RG_MAX_LIGHTS:
-- the lists' 16-bit indices); nothing here is sized by it.

-- How the light loop (shaders/lib/lighting.glsl) evaluates sphere, disk, rectangle and tube lights:
-- "frostbite", the seed's approximations (000 lst:10, 002 §4.7: structured sampling, representative
-- points); "ltc", linearly transformed cosines (shaders/lib/ltc.glsl), the lobe integrated over the
-- light with the horizon clipped. A field of the scene's light block: switching it rebuilds nothing.
rg.param "area_lights" { type = "choice", default = "ltc", choices = { "ltc", "frostbite" }, scene = "area_light_model",
    doc = "area-light model: frostbite (seed 002 §4.7) or ltc (linearly transformed cosines)" }
-- Every sphere, disk, rect and tube light drawn as its emissive shape at its luminance (seed 002
-- §4.8; graph/runtime/light_shapes.h): the scene gains a mesh per light when it loads. A light's
-- own `visible = false` hides one; this hides them all (a study of the light's lighting alone).
rg.param "light_shapes" { type = "boolean", default = true,
    doc = "draw the area lights' emissive shapes (seed 002 §4.8); read when the scene loads" }

-- The grid's defines (the column size and slices every froxel writer and reader shares), with `extra`.
local function froxel_defines(extra)
    local d = { RG_COARSE_TILE_SIZE = lighting.coarse_tile, RG_FROXEL_SLICES = lighting.froxel_slices }
    for k, v in pairs(extra or {}) do d[k] = v end
    return d
end
rg.buffer "light_froxel_counts" {
    size = 16, tile = lighting.coarse_tile, tile_bytes = 4 * lighting.froxel_slices,
    doc = "per froxel (32x32-pixel column, slice of view distance) how many ranged lights reach it",
}
rg.buffer "light_froxels" {
    size = 4, tile = lighting.coarse_tile, tile_bytes = 4 * lighting.froxel_slices * lighting.froxel_words,
    doc = "per froxel the ranged lights that reach it, ascending (light_froxels.comp)",
}
rg.buffer "light_tiles" {
    size = 16, tile = lighting.tile, tile_bytes = 4 * lighting.tile_words,
    doc = "per 4x4 tile the ranged lights that reach its surfaces (light_culling.comp)",
}
rg.buffer "light_spheres" {
    size = 16, scene_count = "lights", count_bytes = 16,
    doc = "per light its sphere of influence in view space this frame (xyz the centre, w the range with a margin), written by the binning for the fine culling's test (light_froxels.comp)",
}
rg.buffer "light_froxels_large" {
    size = 16, scene_count = "lights", count_bytes = 4,
    doc = "the lights whose share of the binning would test too many froxels (a count, then their indices), binned by light_froxels_large",
}
rg.pass "light_froxels_clear" {
    kind = "clear", writes = { "light_froxel_counts", "light_froxels_large" }, insert = { after = "gbuffer" },
}
rg.pass "light_froxels" {
    kind = "compute", shader = "passes/light_froxels.comp", groups = { lighting.froxel_groups, 1, 1 },
    reads = { "depth" },
    writes = { { "light_froxel_counts", as = "storage_rw" }, { "light_froxels", as = "storage" }, { "light_spheres", as = "storage" },
               { "light_froxels_large", as = "storage_rw" } },
    insert = { after = "light_froxels_clear" }, defines = froxel_defines(),
}
-- The lights the binning left because a share of theirs would test more froxels than
-- RG_FROXEL_LARGE_WORK (a light across the frame, or many columns at 4K): every invocation of the
-- dispatch takes a share of their columns (lavapipe ends a shader's loops after 65 535
-- iterations in all, so one invocation cannot walk a 4K frame's 130 000 froxels).
rg.pass "light_froxels_large" {
    kind = "compute", shader = "passes/light_froxels.comp", groups = { lighting.froxel_large_groups, 1, 1 },
    reads = { "depth", { "light_froxels_large", as = "storage" } },
    writes = { { "light_froxel_counts", as = "storage_rw" }, { "light_froxels", as = "storage_rw" } },
    insert = { after = "light_froxels" }, defines = froxel_defines { RG_FROXEL_LARGE = true },
}
rg.pass "light_froxels_sort" {
    kind = "compute", shader = "passes/light_froxels.comp", groups = { lighting.sort_groups, 1, 1 },
    reads = { "depth", { "light_froxel_counts", as = "storage" } },
    writes = { { "light_froxels", as = "storage_rw" } },
    insert = { after = "light_froxels_large" },
    defines = froxel_defines { RG_FROXEL_SORT = true },
}
rg.pass "light_culling" {
    kind = "compute", shader = "passes/light_culling.comp",
    reads = { "depth", { "light_froxel_counts", as = "storage" }, { "light_froxels", as = "storage" }, { "light_spheres", as = "storage" } },
    writes = { { "light_tiles", as = "storage" } },
    dispatch = "depth", tile = lighting.tile, insert = { after = "light_froxels_sort" },
    defines = froxel_defines { RG_TILE_SIZE = lighting.tile },
}

-- Adds `reads` to a pass declaration's reads and `define` to its defines: what the `.lit` and
-- `.tiled` wrappers of the lighting modules (ibl, shadows, ao and this one) do. Returns the pass.
function lighting.extend(pass, reads, define)
    pass.reads = pass.reads or {}
    for _, r in ipairs(reads) do table.insert(pass.reads, r) end
    pass.defines = pass.defines or {}
    pass.defines[define] = true
    return pass
end

-- Passes that work on the pixels of one stencil class only (a material's lighting path, a G-buffer
-- fix-up): `lighting.per_class("pass", "class")` registers one, and `lighting.frame(ctx)` (called
-- by render_loop.lua's loop.frame) switches it off while the scene draws nothing of its class
-- (ctx.scene.classes). A stencil-tested pass over no pixel still loads and stores its targets: the
-- default scene, all standard, spared its clear-coat and two-colour lighting and the foliage
-- fix-up ~4.5 ms a frame at 1280x720 on lavapipe.
lighting.class_passes = {}
function lighting.per_class(pass, class)
    table.insert(lighting.class_passes, { pass = pass, class = class })
end
function lighting.frame(ctx)
    if not ctx.scene then return end
    for _, p in ipairs(lighting.class_passes) do ctx.pass(p.pass).auto_enabled = (ctx.scene.classes[p.class] or 0) > 0 end
end

-- A pass that lights surfaces the G-buffer does not hold (forward: blended surfaces), reading the
-- froxel grid at each fragment's depth: adds the froxel buffers to its reads and RG_LIGHT_FROXELS to
-- its defines. Returns the table it was given.
function lighting.clustered(pass)
    lighting.extend(pass, { { "light_froxel_counts", as = "storage" }, { "light_froxels", as = "storage" } }, "RG_LIGHT_FROXELS")
    -- The grid as the froxel passes build it (lib/light_tiles.glsl's readers need its columns and slices).
    for k, v in pairs(froxel_defines()) do pass.defines[k] = v end
    return pass
end

-- A lighting pass's declaration, reading the tile lists: adds `light_tiles` to its reads and
-- RG_LIGHT_TILES to its defines. Returns the table it was given.
function lighting.tiled(pass)
    return lighting.extend(pass, { { "light_tiles", as = "storage" } }, "RG_LIGHT_TILES")
end

-- The deferred lighting pass of a lighting path that has a shading function, as a declaration to
-- give rg.pass: rgraph generates its shader, `lighting_path_<PATH>.frag` (the path's layout
-- unpacked from the G-buffer, shaded by the path's rgShade at the pixel's world position, written
-- pre-exposed), so a material package writes no lighting shader and no binding. The pass reads
-- the G-buffer (`targets`, default GB0..GB3), depth, the exposure state and the tile lists, adds
-- to `hdr` on the pixels of the stencil class `class`, after `lighting_standard` unless `insert`
-- says otherwise; wrap it in the light it gathers (ibl.lit, shadows.masked, ao.lit, ...):
--
--   rg.pass "lighting_toon" (ao.lit(shadows.masked(ibl.lit(lighting.path_pass { path = "toon", class = "lit_toon" }))))
--   lighting.per_class("lighting_toon", "lit_toon")  -- off while the scene draws no toon
function lighting.path_pass(o)
    if type(o) ~= "table" or type(o.path) ~= "string" or type(o.class) ~= "string" then
        error("lighting.path_pass: expected { path = \"PATH\", class = \"STENCIL_CLASS\" }", 2)
    end
    local reads = {}
    for _, t in ipairs(o.targets or { "GB0", "GB1", "GB2", "GB3" }) do reads[#reads + 1] = t end
    for _, r in ipairs { "depth", { "depth", as = "depth" }, { "exposure", as = "storage" } } do reads[#reads + 1] = r end
    return lighting.tiled {
        kind = "fullscreen", shader = "lighting_path_" .. o.path .. ".frag",
        reads = reads, writes = { { "hdr", load = true } }, stencil = { class = o.class },
        insert = o.insert or { after = "lighting_standard" },
    }
end

return lighting

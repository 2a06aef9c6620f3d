-- Light culling per screen tile for the deferred lighting passes (seed 000 §4; DESIGN §3).
--
--   local lighting = require "lighting"   -- declares `light_tiles` and the `light_culling` pass
--   rg.pass "lighting_x" (lighting.tiled { kind = "fullscreen", shader = ..., reads = { ... }, ... })
--
-- Culling runs in two levels after the pass named "gbuffer" (shaders/passes/light_culling.comp),
-- each reading its depth: `light_culling_coarse` lists, per 32x32-pixel tile, the ranged lights
-- whose range reaches the tile's surfaces out of all of the scene's; `light_culling` then lists, per
-- 4x4-pixel tile, those of its coarse tile's list that reach its own surfaces. Small tiles keep
-- each pixel's loop to the lights near it; the coarse level keeps their test from costing
-- tiles × lights. `lighting.tiled` makes a lighting pass read the fine lists (the shader's light
-- loop, through lib/light_tiles.glsl, then visits only the tile's lights). A pipeline that never
-- uses `lighting.tiled` loses both passes to the graph's culling, and its shaders loop over all.
local rg = require "rg"

local lighting = {}

-- Pixels per side of the tiles the lighting passes read. Every pixel of a tile loops over the
-- whole list (a pixel out of a light's range still evaluates it: both sides of a branch run on a
-- CPU rasteriser), so the list should hold what reaches the pixel: in the many-lights scene at
-- 640x360 (about four lights a pixel), lighting + culling cost 7.3 ms at 64 lights and 9.8 at
-- 1024 with 8x8 tiles (1.34x: at 1024 the ranges are a quarter as wide, so a tile's footprint
-- adds more lights around them), 7.3-7.9 and 9.2 with 4x4 tiles (~1.21x).
lighting.tile = 4
lighting.coarse_tile = 32    -- pixels per side of the coarse level's tiles
-- Words per fine tile: the count, then up to 62 indices of ranged lights, 16 bits each (128 B per
-- tile; 7 MiB at 1280x720); per coarse tile up to 255, a word each (1 KiB per tile). Lights without a range and the sun
-- reach every pixel and are listed once, in the global list (count + up to 1024 indices,
-- shaders/lib/scene.glsl's RG_MAX_LIGHTS). A tile reached by more ranged lights than its list
-- holds keeps the lowest indices (the `lights` view shows them); a fine tile under an overflowing
-- coarse tile tests every light.
lighting.tile_words = 32
lighting.coarse_words = 256
lighting.max_lights = 1024

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

rg.buffer "light_tiles_coarse" {
    size = 16, tile = lighting.coarse_tile, tile_bytes = 4 * lighting.coarse_words,
    doc = "per 32x32 tile the ranged lights that reach it (light_culling.comp's coarse level)",
}
rg.buffer "light_tiles" {
    size = 16 + 4 * (lighting.max_lights + 1), tile = lighting.tile, tile_bytes = 4 * lighting.tile_words,
    doc = "the lights that reach every pixel, then per 4x4 tile the ranged lights that reach it (light_culling.comp)",
}
rg.pass "light_culling_coarse" {
    kind = "compute", shader = "passes/light_culling.comp",
    reads = { "depth" }, writes = { { "light_tiles_coarse", as = "storage" } },
    dispatch = "depth", tile = lighting.coarse_tile, insert = { after = "gbuffer" },
    defines = { RG_CULL_COARSE = true, RG_COARSE_TILE_SIZE = lighting.coarse_tile },
}
rg.pass "light_culling" {
    kind = "compute", shader = "passes/light_culling.comp",
    reads = { "depth", { "light_tiles_coarse", as = "storage" } }, writes = { { "light_tiles", as = "storage" } },
    dispatch = "depth", tile = lighting.tile, insert = { after = "light_culling_coarse" },
    defines = { RG_TILE_SIZE = lighting.tile },
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

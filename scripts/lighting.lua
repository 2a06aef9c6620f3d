-- Light culling per screen tile for the deferred lighting passes (seed 000 §4; DESIGN §3).
--
--   local lighting = require "lighting"   -- declares `light_tiles` and the `light_culling` pass
--   rg.pass "lighting_x" (lighting.tiled { kind = "fullscreen", shader = ..., reads = { ... }, ... })
--
-- The culling pass (shaders/passes/light_culling.comp) runs after the pass named "gbuffer", reads
-- its depth and lists, per 16x16-pixel tile, the lights whose range reaches the tile's surfaces.
-- `lighting.tiled` makes a lighting pass read that list (the shader's light loop, through
-- lib/light_tiles.glsl, then visits only the tile's lights). A pipeline that never uses
-- `lighting.tiled` loses the culling pass to the graph's culling, and its shaders loop over all.
local rg = require "rg"

local lighting = {}

-- Words per tile: the count, then up to 255 indices of ranged lights (1 KiB per tile; 3.5 MiB at
-- 1280x720). Lights without a range and the sun reach every pixel and are listed once, in the
-- global list (count + up to 1024 indices, shaders/lib/scene.glsl's RG_MAX_LIGHTS). A tile
-- reached by more than 255 ranged lights keeps the first 255 (the `lights` view shows them).
lighting.tile_words = 256
lighting.max_lights = 1024

rg.buffer "light_tiles" {
    size = 16 + 4 * (lighting.max_lights + 1), tile = 16, tile_bytes = 4 * lighting.tile_words,
    doc = "the lights that reach every pixel, then per 16x16 tile the ranged lights that reach it (light_culling.comp)",
}
rg.pass "light_culling" {
    kind = "compute", shader = "passes/light_culling.comp",
    reads = { "depth" }, writes = { { "light_tiles", as = "storage" } },
    dispatch = "depth", tile = 16, insert = { after = "gbuffer" },
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

-- A lighting pass's declaration, reading the tile lists: adds `light_tiles` to its reads and
-- RG_LIGHT_TILES to its defines. Returns the table it was given.
function lighting.tiled(pass)
    return lighting.extend(pass, { { "light_tiles", as = "storage" } }, "RG_LIGHT_TILES")
end

return lighting

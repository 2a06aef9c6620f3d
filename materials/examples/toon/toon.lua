-- A game team's toon material, as a package of its own: a G-buffer layout, a stencil class, a
-- lighting path with its shading function (deferred and forward), a material with checked
-- parameters and its decal behaviour — Lua and GLSL only, found next to this file wherever the
-- folder lives. A pipeline takes it with `require "toon"` (see pipeline.lua beside it).
local rg = require "rg"
local lighting = require "lighting"  -- its lighting pass loops over the tile's lights
local shadows = require "shadows"    -- shadowed like the standard path
local ibl = require "ibl"            -- the distant probe's diffuse as its ambient
local ao = require "ao"              -- min(material AO, screen-space AO)
require "disney"

-- The toon G-buffer over the render loop's targets, materialId where every layout keeps it
-- (GB0.A): a tint instead of a base colour, the number of bands and the wrap instead of
-- smoothness, metal mask and reflectance.
rg.layout "toon" {
    { "GB0", "rgb10a2",    { "normal:oct:20", "rim:unorm:10", "materialId:uint:2" } },
    { "GB1", "rgba8_srgb", { "tint:srgb:24", "steps:uint:5", "spare:uint:3" } },
    { "GB2", "rgba8",      { "wrap:unorm:8", "reserved:unorm:8x2", "ao:unorm:8" } },
    { "GB3", "rgba16f",    { "emissive:float:16x3" } },
}

rg.stencil "lit_toon" { doc = "toon: banded wrap lighting" }
rg.path "toon" { stencil = "lit_toon", shading = "toon_shading.glsl", doc = "banded wrap diffuse, rim, probe ambient" }

rg.material "toon" {
    id = 3, layout = "toon", path = "toon", surface = "toon.glsl",
    params = { toonBands = 3, toonWrap = 0.3, toonRim = 0.5 },
    -- Decals paint the tint and bend the normal; the bands, wrap and rim are the toon's own.
    channels = { baseColor = "tint" },
    decals = { "normal", "baseColor" },
    doc = "cel-shaded: N·L wrapped and cut into toonBands bands",
}

-- Its deferred lighting: rgraph generates the pass's shader from the path's shading function.
rg.pass "lighting_toon" (ao.lit(shadows.masked(ibl.lit(lighting.path_pass { path = "toon", class = "lit_toon" }))))
lighting.per_class("lighting_toon", "lit_toon")  -- off while the scene has no toon material

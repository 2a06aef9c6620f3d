-- A game team's skin material, as a package of its own: a G-buffer layout without a materialId (a
-- pixel's material is its stencil value, its identity), a stencil class, a lighting path whose
-- shading function wraps the diffuse light further round the terminator in red than in blue (the
-- light that scatters under the skin), and a material with a scatter colour. Lua and GLSL only,
-- found next to this file; a pipeline takes it with `require "skin"` (see pipeline.lua beside it).
local rg = require "rg"
local lighting = require "lighting"  -- its lighting pass loops over the tile's lights
local shadows = require "shadows"    -- shadowed like the standard path
local ibl = require "ibl"            -- the distant probe's diffuse and specular
local ao = require "ao"              -- min(material AO, screen-space AO)
require "disney"

-- Over the render loop's targets: the normal and smoothness where the disney layout keeps them,
-- the base colour in sRGB, the scatter colour (how far each channel wraps) with the AO.
rg.layout "skin" {
    { "GB0", "rgb10a2",    { "normal:oct:20", "smoothness:unorm:10", "spare:uint:2" } },
    { "GB1", "rgba8_srgb", { "baseColor:srgb:24", "unused:uint:8" } },
    { "GB2", "rgba8",      { "scatter:unorm:8x3", "ao:unorm:8" } },
    { "GB3", "rgba16f",    { "emissive:float:16x3" } },
}

rg.stencil "lit_skin" { doc = "skin: per-channel wrapped diffuse, one specular lobe" }
rg.path "skin" { stencil = "lit_skin", shading = "skin_shading.glsl", doc = "cosine-power diffuse per channel (scatter colour), GGX at f0 0.028" }

rg.material "skin" {
    layout = "skin", path = "skin", surface = "skin.glsl",
    -- The scatter colour: 0 is Lambert, 1 the broadest wrap (cos^0.25).
    params = { scatterR = 1.0, scatterG = 0.45, scatterB = 0.3 },
    -- Decals (paint, tattoos) change the colour, the normal and the smoothness; never the scatter.
    decals = { "normal", "baseColor", "smoothness" },
    doc = "wrap-lit skin: the diffuse light reaches further past the light in red than in blue",
}

-- Its deferred lighting: rgraph generates the pass's shader from the path's shading function.
rg.pass "lighting_skin" (ao.lit(shadows.masked(ibl.lit(lighting.path_pass { path = "skin", class = "lit_skin" }))))
lighting.per_class("lighting_skin", "lit_skin")  -- off while the scene has no skin

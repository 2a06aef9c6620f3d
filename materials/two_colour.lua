-- The two-colour base material (seed 000 §3.2, tbl:3): a diffuse colour and an f0 colour instead
-- of Disney's single base colour, metal mask and scalar reflectance, for the specular highlights
-- of metal/dielectric mixes such as metal oxides. Its layout shares GB0, GB1's alpha and GB3 with
-- the disney layout (MaterialId in the same place for every material); GB1's colour holds the
-- diffuse colour (sRGB, like BaseColor) and GB2 the f0 colour with AO. It unpacks to the same
-- lighting inputs as the standard material (diffuse colour, f0, roughness: the Disney -> two-colour
-- conversion is the one the standard lighting does when it unpacks, fig:14), so its lighting pass
-- runs the standard BRDF and light loop on its own stencil class.
local rg = require "rg"
local lighting = require "lighting"
local ibl = require "ibl"  -- lit by the distant light probe too
local reflections = require "reflections"  -- and the reflection composed from SSR, local and distant probes
local ao = require "ao"    -- its ambient occlusion: min(material AO, screen-space AO)
local shadows = require "shadows"  -- its lights shadowed as the standard path's
require "disney"

rg.layout "two_colour" {
    { "GB0", "rgb10a2",    { "normal:oct:20", "smoothness:unorm:10", "materialId:uint:2" } },
    { "GB1", "rgba8_srgb", { "diffuseColor:srgb:24", "materialData:uint:5", "normalExtra:uint:3" } },
    -- f0 linear in 8 bits: below 2 % it reads as micro-occlusion (f90 = saturate(50 · f0),
    -- lst:2) as Reflectance's low range does.
    { "GB2", "rgba8",      { "f0:unorm:8x3", "ao:unorm:8" } },
    { "GB3", "rgba16f",    { "emissive:float:16x3" } },
}

rg.stencil "lit_two_colour" { doc = "two-colour base material: standard BRDF from diffuse and f0 colours" }
rg.path "two_colour" { stencil = "lit_two_colour", shading = "two_colour_shading.glsl", doc = "the standard light loop over the two_colour layout" }
rg.material "two_colour" {
    id = 2, layout = "two_colour", path = "two_colour", surface = "materials/two_colour.glsl",
    -- Decals blend their base colour into the diffuse colour; debug views show it as base colour
    -- and the f0 colour (its own name) as reflectance.
    channels = { baseColor = "diffuseColor" },
    -- glTF's specularGlossinessTexture: RGB times f0, A times the smoothness (two_colour.glsl).
    textures = { "specularGlossinessMap" },
    doc = "two-colour base material, seed 000 tbl:3",
}

rg.pass "lighting_two_colour" (reflections.lit(shadows.masked(ao.lit(ibl.lit(
    lighting.path_pass { path = "two_colour", class = "lit_two_colour" })))))
lighting.per_class("lighting_two_colour", "lit_two_colour")  -- off while the scene has no two-colour material

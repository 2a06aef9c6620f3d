-- A cloth material (glTF's KHR_materials_sheen; the seeds have no cloth model): the standard base —
-- Disney diffuse and GGX, f0 4 % or a metal's base colour — under a sheen lobe, Estevez and Kulla's
-- "Charlie" distribution with Neubelt and Pettineo's visibility (shaders/lib/brdf.glsl), whose
-- colour is the sheen's reflectance. What the sheen reflects the base does not: it is scaled by
-- 1 − max(sheen colour) · E, E the lobe's directional albedo at the view (the DFG table's w,
-- shaders/ibl/dfg.comp), for the lights and the probes alike. Its layout keeps the normal and the
-- smoothness where the disney layout does (SSR, decals and views read them there), the sheen colour
-- with the AO, and the sheen roughness beside the base colour; the reflectance is the default 0.5
-- (f0 4 %, glTF's IOR 1.5), the metal mask rides with the emission. No materialId: a pixel's
-- stencil value names its material.
local rg = require "rg"
local lighting = require "lighting"
local ibl = require "ibl"  -- lit by the distant light probe, and E from its DFG table
local reflections = require "reflections"  -- the reflection composed from SSR, local and distant probes
local ao = require "ao"    -- its ambient occlusion: min(material AO, screen-space AO)
local shadows = require "shadows"  -- its lights shadowed as the standard path's
require "disney"

rg.layout "sheen" {
    { "GB0", "rgb10a2",    { "normal:oct:20", "smoothness:unorm:10", "spare:uint:2" } },
    { "GB1", "rgba8_srgb", { "baseColor:srgb:24", "sheenRoughness:unorm:8" } },
    -- The sheen colour linear in 8 bits (GB2 is not an sRGB target): steps of 1/255.
    { "GB2", "rgba8",      { "sheenColor:unorm:8x3", "ao:unorm:8" } },
    { "GB3", "rgba16f",    { "emissive:float:16x3", "metalMask:float:16" } },
}

rg.stencil "lit_sheen" { doc = "sheen: the standard lobes under a Charlie sheen lobe" }
rg.path "sheen" { stencil = "lit_sheen", shading = "sheen_shading.glsl",
                  doc = "the standard BRDF scaled by 1 − max(sheen) E, plus the Charlie sheen lobe" }
rg.material "sheen" {
    layout = "sheen", path = "sheen", surface = "materials/sheen.glsl",
    -- glTF's sheenColorFactor and sheenRoughnessFactor (a white sheen of roughness 0.5 when a Lua
    -- scene names the model without them).
    params = { sheenColorR = 1.0, sheenColorG = 1.0, sheenColorB = 1.0, sheenRoughnessFactor = 0.5 },
    -- glTF's sheenColorTexture (RGB, sRGB) and sheenRoughnessTexture (A), times the factors.
    textures = { "sheenColorMap", "sheenRoughnessMap" },
    decals = { "normal", "baseColor", "smoothness" },
    doc = "cloth: a Charlie sheen lobe over the standard base (glTF KHR_materials_sheen)",
}

rg.pass "lighting_sheen" (reflections.lit(shadows.masked(ao.lit(ibl.lit(
    lighting.path_pass { path = "sheen", class = "lit_sheen" })))))
lighting.per_class("lighting_sheen", "lit_sheen")  -- off while the scene has no sheen material

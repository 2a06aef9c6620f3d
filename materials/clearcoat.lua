-- A game team's clear-coat material, declared in Lua and GLSL only: its own layout, stencil class
-- and lighting path, whose lighting pass evaluates the lights twice (seed 000 §3.2.2: "a clear coat
-- model that needs to sample the lighting twice"): the base layer, attenuated by what the coat
-- reflects, plus a second GGX lobe for the coat. The coat has a normal of its own (glTF's
-- KHR_materials_clearcoat: the vertex normal, or its clearcoatNormalTexture — not the base's
-- normal map, under a smooth coat), so its layout keeps two: the base's where the disney layout
-- keeps it (SSR, decals, AO and the views read it there), the coat's in 16 bits beside the coat's
-- smoothness and the metal mask in GB2; the coat's strength beside the base colour; the AO beside
-- the emission. The base's reflectance is fixed at 0.5 (f0 4 %, glTF's IOR 1.5).
local rg = require "rg"
local lighting = require "lighting"
local ibl = require "ibl"  -- lit by the distant light probe too
local probes = require "probes"  -- and reflecting the local ones
local ssr = require "ssr"        -- and the screen-space reflection over them
local reflections = require "reflections"  -- composed by their own pass
local ao = require "ao"    -- its ambient occlusion: min(material AO, screen-space AO)
local shadows = require "shadows"  -- its lights shadowed as the standard path's
require "disney"

rg.layout "clearcoat" {
    { "GB0", "rgb10a2",    { "normal:oct:20", "smoothness:unorm:10", "spare:uint:2" } },
    { "GB1", "rgba8_srgb", { "baseColor:srgb:24", "coatWeight:unorm:8" } },
    { "GB2", "rgba8",      { "coatNormal:oct:16", "coatGloss:unorm:8", "metalMask:unorm:8" } },
    { "GB3", "rgba16f",    { "emissive:float:16x3", "ao:float:16" } },
}

rg.stencil "lit_clearcoat" { doc = "clear coat: two specular lobes" }
rg.path "clearcoat" { stencil = "lit_clearcoat", shading = "clearcoat_shading.glsl" }
rg.material "clear_coat" {
    layout = "clearcoat", path = "clearcoat", surface = "materials/clearcoat.glsl",
    -- glTF's clearcoatFactor, 1 − clearcoatRoughnessFactor and clearcoatNormalTexture.scale.
    params = { coatSmoothness = 0.9, coatStrength = 1.0, coatNormalScale = 1.0 },
    -- Its own textures (a scene material's `textures`, glTF's clearcoatTexture,
    -- clearcoatRoughnessTexture and clearcoatNormalTexture): R times the strength, G times the
    -- coat's roughness, the coat's tangent-space normal (the vertex normal without one).
    textures = { "coatStrengthMap", "coatRoughnessMap", "coatNormalMap" },
}

-- Lights the clear-coat pixels right after the standard ones (the low 3 stencil bits name the path).
rg.pass "lighting_clearcoat" (reflections.lit(ssr.lit(shadows.masked(ao.lit(probes.lit(ibl.lit(
    lighting.path_pass { path = "clearcoat", class = "lit_clearcoat" })))))))
lighting.per_class("lighting_clearcoat", "lit_clearcoat")  -- off while the scene has no clear coat

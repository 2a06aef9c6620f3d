-- A game team's clear-coat material, declared in Lua and GLSL only: its own materialId, stencil
-- class and lighting path, whose lighting pass evaluates the lights twice (seed 000 §3.2.2: "a
-- clear coat model that needs to sample the lighting twice"): the base layer, attenuated by what
-- the coat reflects, plus a second GGX lobe for the coat. Coat smoothness goes into the disney
-- layout's spare GB2.r channel, coat strength into GB1.a's 5-bit MaterialData.
local rg = require "rg"
local lighting = require "lighting"
local ibl = require "ibl"  -- lit by the distant light probe too
local probes = require "probes"  -- and reflecting the local ones
local ssr = require "ssr"        -- and the screen-space reflection over them
local reflections = require "reflections"  -- composed by their own pass
local ao = require "ao"    -- its ambient occlusion: min(material AO, screen-space AO)
local shadows = require "shadows"  -- its lights shadowed as the standard path's
require "disney"

rg.stencil "lit_clearcoat" { doc = "clear coat: two specular lobes" }
rg.path "clearcoat" { stencil = "lit_clearcoat", shading = "clearcoat_shading.glsl" }
rg.material "clear_coat" {
    id = 1, layout = "disney", path = "clearcoat", surface = "materials/clearcoat.glsl",
    params = { coatSmoothness = 0.9, coatStrength = 1.0 },
    -- Its own textures (a scene material's `textures`, glTF's clearcoatTexture and
    -- clearcoatRoughnessTexture): R times the strength, G times the coat's roughness.
    textures = { "coatStrengthMap", "coatRoughnessMap" },
}

-- Lights the clear-coat pixels right after the standard ones (the low 3 stencil bits name the path).
rg.pass "lighting_clearcoat" (reflections.lit(ssr.lit(shadows.masked(ao.lit(probes.lit(ibl.lit(
    lighting.path_pass { path = "clearcoat", class = "lit_clearcoat" })))))))
lighting.per_class("lighting_clearcoat", "lit_clearcoat")  -- off while the scene has no clear coat

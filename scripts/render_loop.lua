-- The G-buffer half of Frostbite's render loop (seed 000 §3.2.2, §3.3), shared by
-- pipelines/deferred.lua and pipelines/reference.lua: the materials, the targets of the disney
-- layout (tbl:2) with depth/stencil and the HDR the lighting writes, the `gbuffer` scene pass
-- (stencil classes from the materials; the foliage fix-up inserts itself after it) and the
-- deferred decals.
--
--   local loop = require "render_loop"
--   rg.pass "lighting_..." { ... }                 -- the lighting passes write `hdr`
--   loop.sky_and_forward()                         -- the sky, then blended materials
--   function rg.frame(ctx) loop.frame(ctx) end     -- skips the decal passes without decals
local rg = require "rg"
-- Each pixel's screen motion since the last frame (scripts/motion.lua), for TAA (post.chain's
-- `motion`), SSR's and AO's histories to reproject by: written by the G-buffer pass from every
-- draw's last world matrix and the last frame's camera, and by the forward pass over it for
-- blended surfaces (with their opacity). It exists only while a node of the scene moves: where
-- nothing moves, a pixel's motion is the camera's alone and is found exactly from the depth.
-- Declared first: the material packages' lighting passes bring SSR's and AO's passes, which read it.
require("motion").declare()

require "disney"     -- the standard material, its layout (tbl:2), stencil class and lighting path
require "clearcoat"  -- a game team's clear-coat material and its lighting path
require "foliage"    -- a game team's foliage material and its G-buffer fix-up
require "two_colour" -- the two-colour base material (tbl:3) and its lighting path
require "sheen"      -- a cloth material (glTF KHR_materials_sheen) and its lighting path
require "transmission"  -- glass and liquids (glTF KHR_materials_transmission, _volume), forward only

local ibl = require "ibl"   -- the distant light probe: the forward pass is lit by it too
local shadows = require "shadows"  -- the sun's shadow map: and shadowed by it
local probes = require "probes"    -- the local light probes: reflected by it
local lighting = require "lighting"  -- the passes of each material's stencil class (lighting.per_class)

local loop = {}

rg.resource "GB0" { format = "rgb10a2" }
rg.resource "GB1" { format = "rgba8_srgb" }
rg.resource "GB2" { format = "rgba8" }
rg.resource "GB3" { format = "rgba16f" }
rg.resource "depth" { format = "d32f_s8" }
rg.resource "hdr" { format = "rgba16f" }

-- The baked lightmap's specular radiance along each pixel's reflection (seed 003; lib/lightmap.glsl),
-- written by every material when the scene has a lightmap (black otherwise); the reflection
-- composition takes it instead of the distant probe where SSR and the local probes leave off.
-- It exists only while the scene has a baked lightmap and the lightmap_specular parameter is on
-- (only_when): otherwise it and every access to it leave the graph, and the passes that read it
-- lose RG_LIGHTMAP_SPECULAR.
rg.resource "lightmap_specular" { format = "rgba16f",
    only_when = { scene = "lightmap", param = "lightmap_specular", defines = { "RG_LIGHTMAP_SPECULAR" } } }
require("lightmap").gbuffer_writes_specular = true

-- The opaque frame — the lit opaque surfaces, the sky and the lines — for the transmission material
-- (materials/transmission.lua) to see through: copied before the forward pass draws over it and
-- filtered into mips (a rough surface reads a coarser one). It exists only while the scene draws a
-- transmission material (only_when): otherwise it, its copy and mips leave the graph, and the
-- forward pass loses RG_OPAQUE.
rg.resource "opaque" { format = "rgba16f", mips = "full",
    only_when = { scene = "material:transmission", defines = { "RG_OPAQUE" } } }

-- Specular anti-aliasing in the scene passes (lib/material.glsl, rgSpecularAntialiasing; seed
-- 002 §5.3's pre-filtering): the normal's variance over a pixel — from the normal map's filtered
-- length (Toksvig) and the shading normal's screen-space derivatives (Kaplanyan et al. 2016) —
-- widens the GGX roughness, so highlights on dense normal detail do not sparkle. Compiled in.
rg.param "specular_aa" { type = "boolean", default = true, doc = "specular anti-aliasing in the G-buffer and forward passes" }
rg.param "specular_aa_variance" { type = "number", default = 0.0417, min = 0, max = 1,
    doc = "σ² of the screen-space term: 1/24, a box pixel's (the normal's variance per slope axis over it, per unit of its derivatives)" }
rg.param "specular_aa_threshold" { type = "number", default = 0.18, min = 0, max = 1,
    doc = "κ: the most the screen-space term adds to the GGX α²" }
loop.specular_aa = { specular_aa = "RG_SPECULAR_AA", specular_aa_variance = "RG_SPECULAR_AA_VARIANCE",
                     specular_aa_threshold = "RG_SPECULAR_AA_THRESHOLD" }

-- It reads the exposure state for emission given relative to the exposure (a scene material's
-- emissive_unit = "ev", glTF's emissive): 2^(EV100 + EC − 3), EV100 the last frame's.
-- In a scene of many draws the GPU chooses them (scripts/culling.lua).
local culling = require "culling"
culling.declare()
rg.pass "gbuffer" (culling.gbuffer { kind = "scene", writes = { "GB0", "GB1", "GB2", "GB3", "lightmap_specular", "motion", "depth" },
    reads = { { "exposure", as = "uniform" } }, defines = { RG_EMISSIVE_EV = true },
    lightmap_specular = "lightmap_specular", motion = "motion", switches = loop.specular_aa })

-- Deferred decals (seed 000 §3.3) after the fix-up: the pass reads copies of GB0..GB2 (there is no
-- programmable blending), blends Normal/BaseColor/Smoothness (MetalMask/Reflectance on the
-- standard material only) of the scene's decal boxes and re-packs each pixel with the layout of
-- its material, which the stencil names.
loop.decal_passes = { "decals_copy0", "decals_copy1", "decals_copy2", "decals" }
for i = 0, 2 do
    rg.resource("GB" .. i .. "_in") { format = ({ "rgb10a2", "rgba8_srgb", "rgba8" })[i + 1] }
    rg.pass("decals_copy" .. i) { kind = "copy", reads = { "GB" .. i }, writes = { "GB" .. i .. "_in" } }
end
rg.pass "decals" {
    kind = "fullscreen", shader = "passes/decals.frag",
    reads = { "GB0_in", "GB1_in", "GB2_in", "depth", { "depth", as = "stencil" } },
    writes = { { "GB0", load = true }, { "GB1", load = true }, { "GB2", load = true } },
}

-- After the lighting: the sky (the scene's environment, lib/environment.glsl) where nothing was drawn (depth still at the far plane; "equal" would
-- depend on the rasteriser reproducing 1.0 exactly, less_equal against the cleared 1.0 does not),
-- then the scene's points and lines, then the blended materials, lit directly with the same light loop over their froxels' lights
-- (lighting.clustered), over the lit HDR (back to front). Returns the forward pass's name.
function loop.sky_and_forward()
    rg.pass "sky" {
        kind = "fullscreen", shader = "passes/sky.frag",
        reads = { { "depth", as = "depth" }, { "exposure", as = "uniform" } }, writes = { { "hdr", load = true } },
        depth = { compare = "less_equal", value = 1 },
    }
    -- The scene's points and lines (glTF POINTS and LINES), unlit as viewers draw them, one
    -- pixel wide, before the blended surfaces that may lie in front of them.
    rg.pass "lines" {
        kind = "scene", lines = true,
        reads = { { "depth", as = "depth" }, { "exposure", as = "uniform" } }, writes = { { "hdr", load = true } },
    }
    -- What the transmission material sees through (`opaque`, above): the frame so far, with mips
    -- (a blit chain).
    rg.pass "opaque_copy" { kind = "copy", reads = { "hdr" }, writes = { "opaque" } }
    rg.pass "opaque_mips" { kind = "mips", writes = { { "opaque", load = true } } }
    rg.pass "forward" (lighting.clustered(shadows.lit(probes.lit(ibl.lit {
        kind = "scene", forward = true, switches = loop.specular_aa,
        reads = { { "depth", as = "depth" }, { "exposure", as = "uniform" }, "opaque" },
        writes = { { "hdr", load = true }, { "motion", load = true } }, motion = "motion",
        defines = { RG_OPAQUE = true },
    }))))
    loop.forward_pass = "forward"
    return "forward"
end

-- Per frame: a scene without decals skips the decal passes and their copies of the G-buffer (on
-- lavapipe even a pass that discards every pixel loads and stores its three targets: ~30 ms at 720p);
-- without a sun, no shadow draws; without local probes, no capture; without draws of a material's
-- stencil class, its lighting pass (and the foliage's fix-up).
function loop.frame(ctx)
    shadows.frame(ctx)  -- no sun: the shadow map is only cleared
    probes.frame(ctx)   -- no local probes: nothing captured
    lighting.frame(ctx)  -- no draws of a class: its lighting pass and fix-up are off
    if ctx.scene then
        for _, pass in ipairs(loop.decal_passes) do ctx.pass(pass).auto_enabled = ctx.scene.decals > 0 end
        -- No blended draws, no forward pass: nothing then keeps the sun's maps alive past their
        -- mask passes (scripts/shadows.lua).
        if loop.forward_pass then
            ctx.pass(loop.forward_pass).auto_enabled = ctx.scene.blended > 0
            ctx.pass("lines").auto_enabled = ctx.scene.lines > 0
        end
    end
end

return loop

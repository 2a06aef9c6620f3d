-- Screen-space reflections and their composition with the probes (seed 002 §4.9.4, §4.9.5).
--
--   local ssr = require "ssr"     -- Hi-Z pyramid and SSR, inserted before `lighting_standard`
--   rg.pass "lighting_standard" (ssr.lit { ... })  -- the lighting composes SSR over the probes
--   loop.sky_and_forward()
--
-- `hiz` (compute, per_mip over its own chain) builds the nearest-depth pyramid; `ssr`
-- (fullscreen) marches the reflected ray through it and reads the previous frame's lit image
-- (`hdr_history`, the history of `hdr`, with mips for rough reflections) where the previous
-- frame's camera saw the hit, in nits, with a confidence in alpha (`ssr_trace`: one pixel of each
-- 2×2 block, a different one every frame); `ssr_temporal` accumulates those into `ssr` over
-- frames. All go right before the pass named
-- `lighting_standard` (after the G-buffer, its fix-up and the decals, whichever module requires
-- this first: the materials' own lighting passes take SSR too). A lighting pass wrapped in
-- `ssr.lit` (defines RG_SSR) composes it over the probes' specular, in the same split-sum
-- (lib/ibl.glsl) — scripts/reflections.lua's composition pass does that once per pixel for the
-- G-buffer's lighting paths. `hdr_history` is rg.history's: the graph keeps it (`hdr_history_keep`
-- copies the lit image after every other pass, `hdr_history_mips` fills its mips) and empties it
-- when the passes writing `hdr` change — a lighting pass switched or reloaded — or the camera cuts;
-- an empty history has confidence 0, and the probes reflect.
local rg = require "rg"
local reader = require "gbuffer_reader"  -- the G-buffer decoded by each pixel's material
local lighting = require "lighting"

local ssr = {}

rg.param "ssr_steps" { type = "integer", default = 32, min = 1, max = 256, doc = "Hi-Z march iterations per pixel" }
rg.param "ssr_distance" { type = "number", default = 20, min = 0.1, max = 1000, doc = "metres a reflected ray travels at most" }
rg.param "ssr_thickness" { type = "number", default = 0.3, min = 0.01, max = 10, doc = "metres behind a surface a ray still counts as hitting it" }
rg.param "ssr_max_roughness" { type = "number", default = 0.6, min = 0, max = 1, doc = "linear roughness from which the probes alone reflect" }

rg.resource "hiz" { format = "r32f", mips = "full", doc = "nearest depth pyramid (Hi-Z)" }
rg.param "ssr_feedback" { type = "number", default = 0.85, min = 0, max = 0.98,
    doc = "the share of the last frame's reflection (reprojected, clamped) in each frame's: 0 takes this frame's ray alone" }

rg.resource "ssr_trace" { format = "rgba16f", scale = { 0.5, 0.5 },
    doc = "this frame's ray for each 2×2 block, from the corner ssr_pixel.glsl turns to: rgb luminance (nits), a confidence (−1: unknown)" }
rg.resource "ssr" { format = "rgba16f", scale = { 0.5, 0.5 }, history = "ssr_history",
    doc = "screen-space reflection at half resolution, accumulated over frames (the composition reads it bilinearly): rgb luminance (nits), a confidence" }
rg.resource "ssr_distance" { format = "r16f", scale = { 0.5, 0.5 }, history = "ssr_distance_history",
    doc = "the view distance (m) at each `ssr` texel's block, for the next frame's reprojection; 0: nothing accumulated" }
-- (The mips: a blit chain, the mips kind — per frame ~2.3 ms, against ~5.3 as post/downsample.comp.)
rg.history "hdr_history" { of = "hdr", mips = "full", doc = "the previous frame's lit image, with mips" }

rg.pass "hiz" {
    kind = "compute", shader = "passes/hiz.comp", reads = { "depth" }, writes = { { "hiz", as = "storage" } },
    per_mip = true, filter = "nearest", insert = { before = "lighting_standard" },
}
-- Only the pixels that trace a ray: `ssr_mask` marks them in a half-resolution depth mask (0:
-- something drawn, smooth enough) and `ssr` runs depth-tested over it, so the blocks without a ray
-- (the sky, rough surfaces) are never shaded and keep the cleared 0 — what ssr.frag writes there.
rg.resource "ssr_mask" { format = "d16", scale = { 0.5, 0.5 }, doc = "SSR's half-resolution pixels that trace a ray: depth 0" }
rg.pass "ssr_mask" {
    kind = "fullscreen", shader = "ssr/ssr_mask.frag", reads = reader.reads { "depth" }, writes = { { "ssr_mask", as = "depth" } },
    filter = "nearest", insert = { before = "lighting_standard" }, depth = { compare = "always", value = 1, write = true },
    defines = { RG_SSR_TEMPORAL = true },
}
rg.pass "ssr" (require("motion").reads {
    kind = "fullscreen", shader = "ssr/ssr.frag", reads = reader.reads { "depth", "hiz", "hdr_history", { "exposure", as = "uniform" }, { "ssr_mask", as = "depth" } },
    writes = { "ssr_trace" }, insert = { before = "lighting_standard" }, depth = { compare = "greater", value = 0.5 },
    defines = { RG_SSR_TEMPORAL = true },
})
-- Over frames: `ssr` traces a different corner of each block every frame and `ssr_temporal`
-- blends each texel's ray into its reprojected history (ssr/ssr_temporal.frag; the histories kept
-- by `ssr_history_keep` and `ssr_distance_history_keep`, emptied by a camera cut or a rebuilt pass).
rg.pass "ssr_temporal" (require("motion").reads {
    kind = "fullscreen", shader = "ssr/ssr_temporal.frag", reads = { "ssr_trace", "ssr_history", "ssr_distance_history", "hiz", { "ssr_mask", as = "depth" } },
    writes = { "ssr", "ssr_distance" }, insert = { before = "lighting_standard" }, filter = "nearest",
    depth = { compare = "greater", value = 0.5 },
})

-- A lighting pass's declaration that composes SSR over the probes (lib/ibl.glsl RG_SSR): reads
-- `ssr`. The `ssr` pass decodes each pixel's normal and smoothness with its material's layout
-- (gbuffer_reader.lua), so every lighting path may take it.
function ssr.lit(pass)
    return lighting.extend(pass, { "ssr" }, "RG_SSR")
end

-- Kept for pipelines written when the history was kept by hand: it keeps itself now.
function ssr.history() end

return ssr

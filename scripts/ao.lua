-- Screen-space ambient occlusion (seed 002 §4.10.1–4.10.3): GTAO at half resolution from the
-- depth buffer (read once at half resolution by `ao_depth`) and the G-buffer's normals
-- (shaders/passes/gtao.frag), then a depth-aware 4×4 filter at half resolution (ao_blur.frag)
-- into `ao_blurred`, accumulated over frames (ao_temporal.frag: gtao's directions turn every
-- frame) into `ao_filtered`, inserted after the pass named "gbuffer" (as the light culling).
--
--   local ao = require "ao"
--   rg.pass "lighting_x" (ao.lit { ... })   -- the lighting takes min(material AO, the screen's)
--
-- With `ao.lit` a lighting shader's rgAmbientOcclusion(materialAo, P) (lib/ibl.glsl) upsamples
-- `ao_filtered` to its pixel by view distance (lib/upsample.glsl) and returns the smaller of it and
-- the material's (the seed's "combined with material AO by min"), which then scales the probe's
-- diffuse and, through computeSpecOcclusion, its specular. Direct light is left to the shadows.
-- `ao_upsample` writes the same upsample to `ssao` (r8: 1 open, 0 closed) for the `ssao` view and
-- captures; the lighting does not read it, so the graph culls it otherwise (it cost ~7 ms a frame
-- at 1280×720 on lavapipe, the upsample inside the lighting ~2-3).
local rg = require "rg"
local reader = require "gbuffer_reader"  -- the G-buffer decoded by each pixel's material
local lighting = require "lighting"

local ao = {}

rg.param "ao_radius" { type = "number", default = 1.0, min = 0.05, max = 10, doc = "metres around a point searched for occluders" }
rg.param "ao_feedback" { type = "number", default = 0.8, min = 0, max = 0.98,
    doc = "the share of the last frame's AO (reprojected) in each frame's: 0 takes this frame's alone" }

rg.resource "ao_depth" { format = "r32f", scale = { 0.5, 0.5 }, doc = "the view distance (m) at each half-resolution texel's pixel 2h; 0: no geometry" }
rg.resource "ao_mask" { format = "d16", scale = { 0.5, 0.5 }, doc = "the half-resolution texels with geometry: depth 0 (1 elsewhere)" }
rg.resource "ao_half" { format = "rg16f", scale = { 0.5, 0.5 }, doc = "GTAO at half resolution, before its blur: AO, view distance (m)" }
-- With the shadows module loaded first (it announces its half-resolution mask in
-- lighting.sun_visibility_half), the blur copies the sun's visibility at each texel into b: the
-- two signals are computed at the same pixels 2h and upsampled by the same view distance, so a
-- lighting pass with both (ao.lit and shadows.masked: RG_SSAO_SUN) upsamples once for the two
-- (~3.5 ms of lighting_standard at 1280×720 on lavapipe).
ao.sun = lighting.sun_visibility_half
local ao_format = ao.sun and "rgba16f" or "rg16f"
rg.resource "ao_blurred" { format = ao_format, scale = { 0.5, 0.5 },
    doc = "the half-resolution AO after its bilateral filter: AO, view distance (m)" .. (ao.sun and ", the sun's half-resolution visibility" or "") }
rg.resource "ao_filtered" { format = ao_format, scale = { 0.5, 0.5 }, history = "ao_history",
    doc = "the half-resolution AO accumulated over frames (as ao_blurred; `ao_history`: the last frame's)" }
rg.resource "ssao" { format = "r8", doc = "screen-space ambient occlusion, 1 open .. 0 closed" }

-- `ao_depth` reads the depth buffer once at half resolution: the view distances gtao marches and
-- a mask of the texels with geometry. gtao and ao_blur run depth-tested over the mask, so the sky's
-- blocks are never shaded and keep the clear, (1, 0): open, no distance — what both shaders wrote
-- there (~22 % of the default frame; gtao ~17.5 -> ~13.7 ms at 1280x720 on lavapipe with the
-- cheaper taps, for ~0.7 ms of ao_depth).
rg.pass "ao_depth" {
    kind = "fullscreen", shader = "passes/ao_depth.frag", reads = { "depth" },
    writes = { "ao_depth", { "ao_mask", as = "depth" } }, insert = { after = "gbuffer" }, filter = "nearest",
    depth = { compare = "always", value = 1, write = true },
}
rg.pass "gtao" {
    kind = "fullscreen", shader = "passes/gtao.frag", reads = reader.reads { "ao_depth", { "ao_mask", as = "depth" } },
    writes = { "ao_half" }, insert = { after = "ao_depth" }, filter = "nearest",
    depth = { compare = "greater", value = 0.5 }, clear = { 1, 0, 0, 0 }, defines = { RG_AO_TEMPORAL = true },
}
rg.pass "ao_blur" {
    kind = "fullscreen", shader = "passes/ao_blur.frag", reads = { "ao_half", { "ao_mask", as = "depth" }, ao.sun },
    writes = { "ao_blurred" }, insert = { after = "gtao" }, filter = "nearest",
    depth = { compare = "greater", value = 0.5 }, clear = { 1, 0, 1, 0 }, defines = ao.sun and { RG_AO_SUN = true } or nil,
}
-- Over frames: gtao turns its directions every frame (RG_AO_TEMPORAL) and `ao_temporal` blends
-- each texel's filtered AO into its reprojected history (passes/ao_temporal.frag; the history
-- kept by `ao_history_keep`, emptied by a camera cut or a rebuilt gtao).
rg.pass "ao_temporal" (require("motion").reads {
    kind = "fullscreen", shader = "passes/ao_temporal.frag", reads = { "ao_blurred", "ao_history", { "ao_mask", as = "depth" } },
    writes = { "ao_filtered" }, insert = { after = "ao_blur" }, filter = "linear",
    depth = { compare = "greater", value = 0.5 }, clear = { 1, 0, 1, 0 },
})
rg.pass "ao_upsample" {
    kind = "fullscreen", shader = "passes/ao_upsample.frag", reads = { "ao_filtered", "depth" }, writes = { "ssao" },
    insert = { after = "ao_temporal" }, filter = "nearest",
}

-- A lighting pass's declaration that takes its ambient occlusion from the screen's too.
function ao.lit(pass)
    lighting.extend(pass, { "ao_filtered" }, "RG_SSAO")
    if ao.sun then pass.defines.RG_SSAO_SUN = true end
    return pass
end

return ao

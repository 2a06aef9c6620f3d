-- Screen-space ambient occlusion (seed 002 §4.10.1–4.10.3): GTAO at half resolution from the
-- depth buffer and the G-buffer's normals (shaders/passes/gtao.frag), then a depth-aware 4×4 filter
-- at half resolution (ao_blur.frag) into `ao_filtered`, inserted after the pass named "gbuffer"
-- (as the light culling).
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
local lighting = require "lighting"

local ao = {}

rg.param "ao_radius" { type = "number", default = 1.0, min = 0.05, max = 10, doc = "metres around a point searched for occluders" }

rg.resource "ao_half" { format = "rg16f", scale = { 0.5, 0.5 }, doc = "GTAO at half resolution, before its blur: AO, view distance (m)" }
rg.resource "ao_filtered" { format = "rg16f", scale = { 0.5, 0.5 }, doc = "the half-resolution AO after its bilateral filter: AO, view distance (m)" }
rg.resource "ssao" { format = "r8", doc = "screen-space ambient occlusion, 1 open .. 0 closed" }

rg.pass "gtao" {
    kind = "fullscreen", shader = "passes/gtao.frag", reads = { "depth", "GB0" }, writes = { "ao_half" },
    insert = { after = "gbuffer" }, filter = "nearest",
}
rg.pass "ao_blur" {
    kind = "fullscreen", shader = "passes/ao_blur.frag", reads = { "ao_half" }, writes = { "ao_filtered" },
    insert = { after = "gtao" }, filter = "nearest",
}
rg.pass "ao_upsample" {
    kind = "fullscreen", shader = "passes/ao_upsample.frag", reads = { "ao_filtered", "depth" }, writes = { "ssao" },
    insert = { after = "ao_blur" }, filter = "nearest",
}

-- A lighting pass's declaration that takes its ambient occlusion from the screen's too.
function ao.lit(pass)
    return lighting.extend(pass, { "ao_filtered" }, "RG_SSAO")
end

return ao

-- Screen-space reflections and their composition with the probes (seed 002 §4.9.4, §4.9.5).
--
--   local ssr = require "ssr"     -- after the G-buffer and decals: Hi-Z pyramid, SSR
--   rg.pass "lighting_standard" { ... }
--   ssr.compose()                 -- after the lighting: SSR replaces the probe where it hit
--   loop.sky_and_forward()
--   ssr.history()                 -- the lit image kept for the next frame's SSR
--
-- `hiz` (compute, per_mip over its own chain) builds the nearest-depth pyramid; `ssr`
-- (fullscreen) marches the reflected ray through it and reads the previous frame's lit image
-- (`hdr_history`, persistent, with mips for rough reflections) at the hit, with a confidence in
-- alpha; `ssr_compose` (fullscreen, standard stencil class) blends SSR over the distant probe's
-- specular with that confidence; `ssr_history_copy` + `ssr_history_mips` keep this frame's lit
-- image for the next.
local rg = require "rg"
local ibl = require "ibl"
local ao = require "ao"

local ssr = {}

rg.param "ssr_steps" { type = "integer", default = 32, min = 1, max = 256, doc = "Hi-Z march iterations per pixel" }
rg.param "ssr_distance" { type = "number", default = 20, min = 0.1, max = 1000, doc = "metres a reflected ray travels at most" }
rg.param "ssr_thickness" { type = "number", default = 0.3, min = 0.01, max = 10, doc = "metres behind a surface a ray still counts as hitting it" }
rg.param "ssr_max_roughness" { type = "number", default = 0.6, min = 0, max = 1, doc = "linear roughness from which the probes alone reflect" }

rg.resource "hiz" { format = "r32f", mips = "full", doc = "nearest depth pyramid (Hi-Z)" }
rg.resource "ssr" { format = "rgba16f", doc = "screen-space reflection: rgb colour (pre-exposed), a confidence" }
rg.resource "hdr_history" { format = "rgba16f", mips = "full", persistent = true, doc = "the previous frame's lit image, with mips" }

rg.pass "hiz" {
    kind = "compute", shader = "ssr/hiz.comp", reads = { "depth" }, writes = { { "hiz", as = "storage" } },
    per_mip = true, filter = "nearest",
}
rg.pass "ssr" {
    kind = "fullscreen", shader = "ssr/ssr.frag", reads = { "GB0", "depth", "hiz", "hdr_history" }, writes = { "ssr" },
}

-- After the lighting passes: SSR over the distant probe on the standard class.
function ssr.compose()
    rg.pass "ssr_compose" (ao.lit(ibl.lit {
        kind = "fullscreen", shader = "ssr/compose.frag",
        reads = { "GB0", "GB1", "GB2", "depth", { "depth", as = "depth" }, "ssr", { "exposure", as = "storage" } },
        writes = { { "hdr", load = true } }, blend = "additive", stencil = { class = "lit_standard", mask = 7 },
    }))
end

-- After everything that lights the HDR: keep it (and its mips) for the next frame.
function ssr.history()
    rg.pass "ssr_history_copy" { kind = "copy", reads = { "hdr" }, writes = { "hdr_history" } }
    rg.pass "ssr_history_mips" { kind = "mips", writes = { "hdr_history" } }
end

return ssr

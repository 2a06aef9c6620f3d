-- Image-based lights composition (seed 002 §4.9.5) as a pass of its own.
--
--   local reflections = require "reflections"   -- the `reflection_compose` pass, before lighting_standard
--   rg.pass "lighting_standard" (reflections.lit(ibl.lit { ... }))  -- reads the composed reflection
--
-- `reflection_compose` (fullscreen, shaders/passes/reflection_compose.frag) writes `reflection`:
-- per pixel, the specular radiance along the dominant direction of its G-buffer normal and
-- roughness, composed in the seed's order — SSR first, then the local probes holding the point by
-- priority until the reflection is complete, then the distant probe — in nits, alpha how much SSR
-- and the local probes covered. It goes right before the pass named `lighting_standard`, after
-- `ssr`. A lighting pass wrapped in `reflections.lit` (defines RG_REFLECTION) weights it by its
-- split-sum DFG and specular occlusion (lib/ibl.glsl rgStandardIbl) instead of composing its own;
-- a lobe other than the pixel's (the clear coat's) still composes its own with the same function.
local rg = require "rg"
local reader = require "gbuffer_reader"  -- the G-buffer decoded by each pixel's material
local lightmap = require "lightmap"  -- the lightmap's reflection, where the G-buffer writes it (render_loop.lua)
local lighting = require "lighting"
require "ibl"     -- the distant probe
require "probes"  -- the local probes
require "ssr"     -- and the screen-space reflection

local reflections = {}

rg.resource "reflection" { format = "rgba16f",
    doc = "the composed specular radiance (nits) along each pixel's dominant direction; alpha: SSR and local probes' share" }

-- Depth-tested against the triangle at depth 1 ("greater": where something was drawn), so that
-- lavapipe's early depth test drops the sky's blocks before shading them (a branch in the shader
-- cannot) and they keep the clear, 0 — what the shader writes there (~23 -> ~19.5 ms at 1280x720).
local compose = {
    kind = "fullscreen", shader = "passes/reflection_compose.frag",
    reads = reader.reads { "depth", { "depth", as = "depth" }, "ssr", "env_specular", { "env_sh", as = "uniform" }, "dfg", "probe_specular" }, writes = { "reflection" },
    defines = { RG_IBL = true, RG_SSR = true, RG_PROBES = true }, insert = { before = "lighting_standard" },
    depth = { compare = "greater", value = 1 },
}
-- With a scene's baked lightmap, its specular radiance takes the distant probe's share.
if lightmap.gbuffer_writes_specular then
    table.insert(compose.reads, "lightmap_specular")
    compose.defines.RG_LIGHTMAP_SPECULAR = true
end
rg.pass "reflection_compose" (compose)

-- A lighting pass's declaration that takes its pixels' specular radiance from `reflection`.
function reflections.lit(pass)
    return lighting.extend(pass, { "reflection" }, "RG_REFLECTION")
end

return reflections

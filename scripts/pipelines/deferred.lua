-- The default pipeline: Frostbite's render loop as a graph (seed 000 §3.2.2, lst:3; DESIGN §3).
-- G-buffer of the standard material (tbl:2) with stencil classes from the materials, deferred
-- lighting per lighting path routed by stencil over per-tile light lists, a sky behind, blended
-- materials forward, then the physical camera and post chain (seed 002 §5).
local rg = require "rg"
local post = require "post"
local lighting = require "lighting"  -- per-tile light lists for the lighting passes
local loop = require "render_loop"  -- the materials, the G-buffer, its scene pass and the decals
local ibl = require "ibl"  -- the distant light probe, filtered once per environment (seed 002 §4.9)
local shadows = require "shadows"  -- the sun's cascaded shadow map (seed 002 §4.10.4)
local ao = require "ao"  -- screen-space ambient occlusion (seed 002 §4.10.3)
require "ssr"  -- screen-space reflections over the probe (seed 002 §4.9.4, §4.9.5)
local probes = require "probes"  -- the scene's local light probes, captured once per scene (§4.9.1.2)
local reflections = require "reflections"  -- SSR, local probes and distant probe composed by their own pass (§4.9.5)
require "lightmap"  -- the scene's baked SG lightmap, when it declares one (seed 003)

post.params { exposure_mode = "auto" }
post.exposure_state()

-- One lighting pass per lighting path, each on its stencil class, each looping over the lights
-- of its pixel's tile (lighting.tiled), then adding the probes' light: the distant probe's diffuse
-- (ibl.lit) and the specular radiance the `reflection_compose` pass composed in §4.9.5's order —
-- SSR, the local probes, the distant probe (reflections.lit) — weighted by the split-sum DFG.
rg.pass "lighting_standard" (reflections.lit(ao.lit(shadows.masked(ibl.lit(lighting.tiled {
    kind = "fullscreen", shader = "passes/deferred_lighting.frag",
    reads = { "GB0", "GB1", "GB2", "GB3", "depth", { "depth", as = "depth" }, { "exposure", as = "storage" } },
    writes = { "hdr" }, stencil = { class = "lit_standard" },  -- and its variants: foliage
})))))

-- The sky where nothing was drawn, then blended materials lit with the same light loop (the lit
-- image is kept for the next frame's reflections by its history, scripts/ssr.lua).
loop.sky_and_forward()

post.chain { input = "hdr", output = "display", depth = "depth", motion = "motion" }
rg.output { display = "display", hdr = "hdr", exposure = "exposure" }

function rg.frame(ctx)
    loop.frame(ctx)  -- no decals in the scene: no decal passes; no sun: no shadow draws; no probes: no capture
    post.frame(ctx)  -- TAA, FXAA or neither: the antialiasing parameter
end

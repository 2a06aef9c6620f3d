-- Local light probes (seed 002 §4.9.1.2, §4.9.3, §4.9.5, appendix F; the scene declares them with
-- scene.probe, scripts/scenes/README.md).
--
--   local probes = require "probes"   -- after require "ibl": the capture and its filtering
--   rg.pass "lighting_x" (probes.lit(ibl.lit { ... }))  -- reflections from the local probes
--   function rg.frame(ctx) probes.frame(ctx) end         -- no probes in the scene: no capture
--
-- Once per build (a new scene, pipeline or size: `cadence = "once"`), never per frame:
--   probe_capture   the `scene` kind with capture = true: every probe's six faces, diffuse only,
--                   metals with f0 as albedo, shadow rays for every light, the distant probe's
--                   diffuse; visibility in alpha (0 where the capture sees nothing: the distant
--                   probe shows there) — shaders/probes/capture.{vert,frag};
--   probe_mips      its mip chain;
--   probe_prefilter the specular pre-filter of the distant probe (shaders/ibl/env_prefilter.comp
--                   with RG_PROBE_ARRAY), alpha filtered with the radiance.
-- `probes.lit` makes a lighting pass reflect them: lib/ibl.glsl's composition (§4.9.5) takes
-- SSR first, then the probes holding the pixel (priority, then the smaller first) with
-- appendix F's parallax correction, distance-based roughness and influence fade, until the
-- reflection is complete, then the distant probe.
local rg = require "rg"
local lighting = require "lighting"
require "ibl"  -- the capture adds the distant probe's diffuse (env_sh, dfg)

local probes = {}

probes.max = 8       -- graph/scene/scene.h kMaxProbes
probes.size = 128    -- texels per face of a capture and of its pre-filtered cube (8 mips; the distant probe's env_specular is 256², 9 mips: a probe's capture dominates its cost)

rg.resource "probe_radiance" { format = "rgba16f", size = { probes.size, probes.size }, cube = true, layers = 6 * probes.max,
    mips = "full", persistent = true, doc = "the probes' captures (nits; alpha: something seen), cube k for probe k, with mips" }
rg.resource "probe_depth" { format = "d32f", size = { probes.size, probes.size }, layers = 6 * probes.max, persistent = true,
    doc = "the captures' depth" }
rg.resource "probe_specular" { format = "rgba16f", size = { probes.size, probes.size }, cube = true, layers = 6 * probes.max,
    mips = 8, persistent = true, doc = "the probes pre-filtered: mip m for linear roughness (m / 7)², alpha the visibility" }

rg.pass "probe_capture" {
    kind = "scene", capture = true, cadence = "once",
    reads = { { "env_sh", as = "uniform" }, "dfg" }, writes = { "probe_radiance", "probe_depth" },
}
rg.pass "probe_mips" {  -- the captures' mip chains (post/downsample.comp, as env_mips)
    kind = "compute", shader = "post/downsample.comp", writes = { { "probe_radiance", as = "storage_rw" } }, bind = { target = "probe_radiance" },
    defines = { RG_LAYERED = true, RG_CUBE = true }, per_mip = true, cadence = "once",
}
rg.pass "probe_prefilter" {
    kind = "compute", shader = "ibl/env_prefilter.comp", defines = { RG_PROBE_ARRAY = true }, cadence = "once",
    reads = { "probe_radiance" }, writes = { { "probe_specular", as = "storage" } }, per_mip = true,
}

-- A lighting pass's declaration, reflecting the local probes: reads `probe_specular`, defines
-- RG_PROBES (the pass must be ibl.lit too). Returns the table it was given.
function probes.lit(pass)
    return lighting.extend(pass, { "probe_specular" }, "RG_PROBES")
end

-- Per frame: a scene without probes captures and filters nothing.
function probes.frame(ctx)
    local any = not ctx.scene or ctx.scene.probes > 0
    for _, pass in ipairs { "probe_capture", "probe_mips", "probe_prefilter" } do ctx.pass(pass).auto_enabled = any end
end

return probes

-- The default pipeline: Frostbite's render loop as a graph (seed 000 §3.2.2, lst:3; DESIGN §3).
-- G-buffer of the standard material (tbl:2) with stencil classes from the materials, deferred
-- lighting per lighting path routed by stencil, a sky behind, then the physical camera and post
-- chain (seed 002 §5). It grows as decals, forward, IBL and SSR land.
local rg = require "rg"
local post = require "post"
local lighting = require "lighting"  -- per-tile light lists for the lighting passes
require "disney"     -- the standard material, its layout (tbl:2), stencil class and lighting path
require "clearcoat"  -- a game team's clear-coat material and its lighting path
require "foliage"    -- a game team's foliage material and its G-buffer fix-up
require "two_colour" -- the two-colour base material (tbl:3) and its lighting path

post.params { exposure_mode = "auto" }
post.exposure_state()
rg.param "sky_luminance" { type = "number", default = 6000, min = 0, max = 1e6, doc = "sky luminance at the zenith, cd/m²" }

-- The G-buffer: one resource per target of the disney layout, plus depth and the stencil classes.
rg.resource "GB0" { format = "rgb10a2" }
rg.resource "GB1" { format = "rgba8_srgb" }
rg.resource "GB2" { format = "rgba8" }
rg.resource "GB3" { format = "rgba16f" }
rg.resource "depth" { format = "d32f_s8" }
rg.resource "hdr" { format = "rgba16f" }

rg.pass "gbuffer" { kind = "scene", writes = { "GB0", "GB1", "GB2", "GB3", "depth" } }

-- Deferred decals (seed 000 §3.3) after the fix-up: the pass reads copies of GB0..GB2 (there is no
-- programmable blending), blends Normal/BaseColor/Smoothness (MetalMask/Reflectance on materialId
-- 0 only) of the scene's decal boxes and re-packs.
for i = 0, 2 do
    rg.resource("GB" .. i .. "_in") { format = ({ "rgb10a2", "rgba8_srgb", "rgba8" })[i + 1] }
end
rg.pass "decals_copy0" { kind = "copy", reads = { "GB0" }, writes = { "GB0_in" } }
rg.pass "decals_copy1" { kind = "copy", reads = { "GB1" }, writes = { "GB1_in" } }
rg.pass "decals_copy2" { kind = "copy", reads = { "GB2" }, writes = { "GB2_in" } }
rg.pass "decals" {
    kind = "fullscreen", shader = "passes/decals.frag",
    reads = { "GB0_in", "GB1_in", "GB2_in", "depth" },
    writes = { { "GB0", load = true }, { "GB1", load = true }, { "GB2", load = true } },
}

-- One lighting pass per lighting path, each on its stencil class, each looping over the lights
-- of its pixel's tile (lighting.tiled).
rg.pass "lighting_standard" (lighting.tiled {
    kind = "fullscreen", shader = "passes/deferred_lighting.frag",
    reads = { "GB0", "GB1", "GB2", "GB3", "depth", { "depth", as = "depth" }, { "exposure", as = "storage" } },
    writes = { "hdr" }, stencil = { class = "lit_standard", mask = 7 },  -- low 3 bits: foliage (9) too
})

-- The sky where nothing was drawn: depth still at the far plane. ("equal" would depend on the
-- rasteriser reproducing 1.0 exactly; less_equal against the cleared 1.0 does not.)
rg.pass "sky" {
    kind = "fullscreen", shader = "passes/sky.frag",
    reads = { { "depth", as = "depth" }, { "exposure", as = "storage" } }, writes = { { "hdr", load = true } },
    depth = { compare = "less_equal", value = 1 },  -- at the far plane: only where nothing was drawn
}

-- Blended materials, lit directly with the same light loop, over the lit HDR (back to front).
rg.pass "forward" {
    kind = "scene", forward = true,
    reads = { { "depth", as = "depth" }, { "exposure", as = "storage" } }, writes = { { "hdr", load = true } },
}

post.chain { input = "hdr", output = "display" }

-- A scene without decals skips the decal passes and their copies of the G-buffer (on lavapipe
-- even a pass that discards every pixel loads and stores its three targets: ~30 ms at 720p).
function rg.frame(ctx)
    if ctx.scene then
        for _, pass in ipairs { "decals_copy0", "decals_copy1", "decals_copy2", "decals" } do
            ctx.pass(pass).enabled = ctx.scene.decals > 0
        end
    end
end
rg.output { display = "display", hdr = "hdr", exposure = "exposure" }

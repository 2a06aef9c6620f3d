-- A game team's foliage material, declared in Lua and GLSL only (seed 000 §3.2.2, lst:3): the
-- geometry-heavy G-buffer pass fills only GB0 and GB1; a fix-up pass fills GB2 and GB3 for its
-- pixels afterwards (global parameters: no metal, one reflectance, AO 1, and, as lst:3, the
-- distant diffuse probe's irradiance at the normal into GB3's radiosity, flagged in GB2's reserved
-- channel so that the lighting does not add the probe's diffuse a second time), so foliage shares
-- the standard lighting pass. Its stencil class is a variant of the standard class (variant_of: the same low bits, a
-- value of its own in the high bits): the standard lighting, testing the low bits, lights it; the
-- fix-up, testing all eight, finds it. After the fix-up its pixels decode as the standard
-- material's: the same layout, and the decals of the standard material.
local rg = require "rg"
require "disney"
require "ibl"  -- env_sh, the distant probe's SH the fix-up reads

rg.stencil "foliage" { variant_of = "lit_standard", doc = "needs the G-buffer fix-up, then standard lighting" }
rg.param "foliage_reflectance" { type = "number", default = 0.35, min = 0, max = 1, doc = "fix-up: reflectance of all foliage" }

rg.material "foliage" {
    id = 0, layout = "disney", stencil = "foliage", surface = "materials/foliage.glsl",
    fills = { "GB0", "GB1" }, fixup = "foliage_fixup",
    -- After the fix-up its pixels are the standard material's: decals blend the same parameters.
    decals = { "normal", "baseColor", "smoothness", "metalMask", "reflectance" },
}

rg.pass "foliage_fixup" {
    kind = "fullscreen", shader = "materials/foliage_fixup.frag",
    reads = { "GB0", "GB1", { "depth", as = "depth" }, { "env_sh", as = "uniform" } },
    writes = { { "GB2", load = true }, { "GB3", load = true } },
    stencil = { class = "foliage" }, insert = { after = "gbuffer" },
}
require("lighting").per_class("foliage_fixup", "foliage")  -- off while the scene has no foliage

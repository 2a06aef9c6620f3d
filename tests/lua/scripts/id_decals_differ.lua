local rg = require "rg"
require "disney"
-- Lit by the standard path, but decals blend less on its pixels: a variant of lit_standard.
rg.material "glossy" { layout = "disney", path = "standard", decals = { "normal" } }
-- Decodes as the standard material: shares its identity.
rg.material "matte" { layout = "disney", path = "standard", decals = { "normal", "baseColor", "smoothness", "metalMask", "reflectance" } }
rg.resource "output" { format = "rgba8" }
rg.pass "fill" { kind = "clear", writes = { "output" } }

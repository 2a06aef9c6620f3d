local rg = require "rg"
require "disney"
rg.path "veil" { shading = "materials/standard_shading.glsl" }
rg.material "veil" { layout = "disney", path = "veil" }
rg.resource "output" { format = "rgba8" }
rg.pass "fill" { kind = "clear", writes = { "output" } }
rg.output "output"

local rg = require "rg"
rg.param "spec" { type = "number", default = 1 }
rg.resource "extra" { format = "rgba16f", only_when = { param = "spec" } }
rg.resource "output" { format = "rgba8" }
rg.pass "fill" { kind = "clear", writes = { "output" } }
rg.output "output"

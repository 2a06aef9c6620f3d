local rg = require "rg"
rg.resource "glass" { format = "rgba16f", only_when = { scene = "material:transmission" } }
rg.resource "extra" { format = "rgba16f", only_when = { scene = "material:" } }
rg.resource "output" { format = "rgba8" }
rg.pass "fill" { kind = "clear", writes = { "output" } }
rg.output "output"

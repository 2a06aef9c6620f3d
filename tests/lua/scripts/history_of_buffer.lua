local rg = require "rg"
rg.buffer "counts" { size = 64 }
rg.resource "out" { format = "rgba8" }
rg.history "counts_history" { of = "counts" }
rg.pass "fill" { kind = "clear", writes = { "out" } }
rg.output "out"

local rg = require "rg"
rg.param "first_phase" { type = "boolean", default = true }
rg.param "size" { type = "number", default = 1 }
rg.resource "output" { format = "rgba8" }
rg.pass "first" { kind = "clear", writes = { "output" }, only_when = { param = { "first_phase", "size" } } }
rg.pass "second" { kind = "clear", writes = { { "output", load = "first" } } }
rg.output "output"

local rg = require "rg"
rg.resource "output" { format = "rgba8" }
rg.pass "first" { kind = "clear", writes = { "output" } }
rg.pass "second" { kind = "fullscreen", shader = "passes/sky.frag", writes = { { "output", load = "frist" } } }
rg.output "output"

local rg = require "rg"
rg.resource "output" { format = "rgba8" }
rg.resource "other" { format = "rgba8" }
rg.pass "first" { kind = "fullscreen", shader = "passes/sky.frag", writes = { { "output", load = "second" } } }
rg.pass "second" { kind = "clear", writes = { "output" } }
rg.pass "third" { kind = "fullscreen", shader = "passes/sky.frag", writes = { { "other", load = "second" } } }
rg.output "output"

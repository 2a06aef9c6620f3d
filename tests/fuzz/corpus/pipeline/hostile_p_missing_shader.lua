local rg = require "rg"
rg.resource "r" { format = "rgba8" }
rg.pass "a" { kind = "fullscreen", shader = "no_such_shader.frag", writes = { "r" } }
rg.output "r"

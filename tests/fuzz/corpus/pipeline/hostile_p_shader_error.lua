local rg = require "rg"
rg.resource "r" { format = "rgba8" }
rg.pass "a" { kind = "fullscreen", shader = "p_bad_shader.frag", writes = { "r" } }
rg.output "r"

local rg = require "rg"
rg.resource "pattern" { format = "rgba16f" }
rg.resource "output" { format = "rgba16f" }
rg.pass "generate" { kind = "compute", shader = "test/pattern.comp", writes = { "pattern" } }
rg.pass "transform" { kind = "fullscreen", shader = "test/transform.frag", reads = { "pattern" }, writes = { "output" }, uniforms = { scale = 1 } }
rg.pass "final" { kind = "readback", reads = { "output" }, side_effect = true }
require "modules.team_tint"
rg.output "output"

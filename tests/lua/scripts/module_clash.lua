local rg = require "rg"
rg.resource "pattern" { format = "rgba16f" }
rg.resource "output" { format = "rgba16f" }
rg.pass "generate" { kind = "compute", shader = "test/pattern.comp", writes = { "pattern" } }
rg.pass "transform" { kind = "fullscreen", shader = "test/transform.frag", reads = { "pattern" }, writes = { "output" }, uniforms = { scale = 1 } }
require "modules.team_clash"
rg.output "output"

local rg = require "rg"
rg.param "scale" { type = "number", default = 1, min = 0, max = 16 }
rg.resource "pattern" { format = "rgba16f" }
rg.resource "output" { format = "rgba16f" }
rg.pass "generate" { kind = "compute", shader = "test/pattern.comp", writes = { "pattern" } }
rg.pass "transform" { kind = "fullscreen", shader = "test/transform.frag", reads = { "pattern" }, writes = { "output" } }
rg.output "output"
function rg.frame(ctx)
    ctx.params.scael = 2
end

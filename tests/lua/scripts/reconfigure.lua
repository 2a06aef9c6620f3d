-- Disables the tint pass on the second frame and enables it again on the third.
local rg = require "rg"
rg.param "scale" { type = "number", default = 1, min = 0, max = 16 }
rg.resource "pattern" { format = "rgba16f" }
rg.resource "output" { format = "rgba16f" }
rg.pass "generate" { kind = "compute", shader = "test/pattern.comp", writes = { "pattern" } }
rg.pass "transform" { kind = "fullscreen", shader = "test/transform.frag", reads = { "pattern" }, writes = { "output" } }
rg.pass "tint" {
    kind = "fullscreen", shader = "test/tint.frag", blend = "additive",
    writes = { { "output", load = true } }, uniforms = { tint = { 0.25, 0, 0, 0 } },
}
rg.output "output"
function rg.frame(ctx)
    if ctx.frame == 1 then ctx.pass("tint").enabled = false end
    if ctx.frame == 2 then ctx.pass("tint").enabled = true end
end

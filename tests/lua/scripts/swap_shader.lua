-- Swaps the transform pass's shader on the second frame.
local rg = require "rg"
rg.resource "pattern" { format = "rgba16f" }
rg.resource "output" { format = "rgba16f" }
rg.pass "generate" { kind = "compute", shader = "test/pattern.comp", writes = { "pattern" } }
rg.pass "transform" {
    kind = "fullscreen", shader = "test/transform.frag", reads = { "pattern" }, writes = { "output" },
    uniforms = { scale = 1, tint = { 0, 0.75, 0, 1 } },
}
rg.output "output"
function rg.frame(ctx)
    if ctx.frame == 1 then ctx.pass("transform").shader = "test/tint.frag" end
end

-- A two-pass test graph: a compute pass writes a colour ramp with a checker (exact in half
-- floats), a fullscreen pass maps it to `output`. Used by the tests and as the smallest example.
local rg = require "rg"

rg.param "scale" { type = "number", default = 1.0, min = 0, max = 16, doc = "multiplies the output" }

rg.resource "pattern" { format = "rgba16f" }
rg.resource "output" { format = "rgba16f" }

rg.pass "generate" { kind = "compute", shader = "test/pattern.comp", writes = { "pattern" } }
rg.pass "transform" {
    kind = "fullscreen", shader = "test/transform.frag",
    reads = { "pattern" }, writes = { "output" },
}

rg.output "output"

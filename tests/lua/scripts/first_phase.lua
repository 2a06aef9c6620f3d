-- A pass that runs only while two parameters are on (only_when), and one that loads what it wrote
-- while it runs and clears otherwise (load = "first"): the G-buffer's two phases in small.
local rg = require "rg"
rg.param "culling" { type = "boolean", default = true }
rg.param "occlusion" { type = "boolean", default = true }
rg.resource "output" { format = "rgba16f" }
rg.pass "first" { kind = "clear", writes = { "output" }, value = { 0.5, 0, 0, 0 },
    only_when = { param = { "culling", "occlusion" } } }
rg.pass "second" {
    kind = "fullscreen", shader = "test/tint.frag", blend = "additive",
    writes = { { "output", load = "first" } }, uniforms = { tint = { 0.25, 0, 0, 0 } },
}
rg.output "output"

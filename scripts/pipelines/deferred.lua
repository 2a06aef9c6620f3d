-- The default pipeline: Frostbite's render loop as a graph (seed 000 §3.2.2, lst:3; DESIGN §3).
-- It declares the material system (G-buffer layout of tbl:2, stencil classes, lighting paths,
-- the standard material) and grows pass by pass as the scene raster, lighting and post passes
-- land. Until the scene raster pass exists, it renders the test card of test.lua.
local rg = require "rg"
require "disney"

rg.param "scale" { type = "number", default = 1.0, min = 0, max = 16, doc = "test card brightness" }

rg.resource "card" { format = "rgba16f" }
rg.resource "output" { format = "rgba16f" }

rg.pass "card" { kind = "compute", shader = "test/pattern.comp", writes = { "card" }, bind = { pattern = "card" } }
rg.pass "present" {
    kind = "fullscreen", shader = "test/transform.frag",
    reads = { "card" }, writes = { "output" }, bind = { pattern = "card" },
}

rg.output "output"

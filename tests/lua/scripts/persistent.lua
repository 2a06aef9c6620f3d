-- A persistent resource keeps its contents across frames: `history` grows by `step` each frame.
local rg = require "rg"
rg.param "step" { type = "number", default = 0.5 }
rg.resource "history" { format = "rgba32f", persistent = true }
rg.resource "output" { format = "rgba32f" }
rg.pass "accumulate" { kind = "compute", shader = "test/accumulate.comp", writes = { { "history", as = "storage_rw" } } }
rg.pass "show" { kind = "copy", reads = { "history" }, writes = { "output" } }
rg.output "output"

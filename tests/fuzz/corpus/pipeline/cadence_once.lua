-- A pass run once: `history` grows by `step` only in the first frame after a build, and again
-- after the persistent resources are cleared (what the environment filtering relies on).
local rg = require "rg"
rg.param "step" { type = "number", default = 0.5 }
rg.resource "history" { format = "rgba32f", persistent = true }
rg.resource "output" { format = "rgba32f" }
rg.pass "accumulate" { kind = "compute", shader = "test/accumulate.comp", writes = { { "history", as = "storage_rw" } }, cadence = "once" }
rg.pass "show" { kind = "copy", reads = { "history" }, writes = { "output" } }
rg.output "output"

-- per_mip = true: one dispatch per mip of `chain`, each writing its mip (rg_mip, rg_mipCount and
-- the mip's size); `gather` copies texel (0, 0) of every mip into a row of `output`.
local rg = require "rg"
rg.resource "chain" { format = "rgba32f", size = { 16, 8 }, mips = "full" }
rg.resource "output" { format = "rgba32f", size = { 8, 1 } }
rg.pass "fill" { kind = "compute", shader = "test/mip_index.comp", writes = { { "chain", as = "storage" } }, per_mip = true }
rg.pass "gather" { kind = "compute", shader = "test/mip_gather.comp", reads = { "chain" }, writes = { { "output", as = "storage" } }, bind = { output_ = "output" } }
rg.output "output"

local rg = require "rg"
rg.resource "taa" { format = "rgba16f", history = "taa_history" }
rg.resource "taa_history" { format = "rgba16f", persistent = true }
rg.pass "fill" { kind = "clear", writes = { "taa" } }
rg.output "taa"

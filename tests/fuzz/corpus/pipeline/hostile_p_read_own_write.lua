local rg = require "rg"
rg.resource "r" { format = "rgba8" }
rg.pass "a" { kind = "copy", reads = { "r" }, writes = { "r" } }
rg.output "r"

local rg = require "rg"
rg.resource "r" { format = "rgba8" }
rg.pass "a" { kind = "copy", reads = { "nope" }, writes = { "r" } }
rg.output "r"

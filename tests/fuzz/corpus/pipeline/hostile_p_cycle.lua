local rg = require "rg"
rg.resource "x" { format = "rgba8" }
rg.resource "y" { format = "rgba8" }
rg.pass "a" { kind = "clear", writes = { "x" }, after = { "b" } }
rg.pass "b" { kind = "copy", reads = { "x" }, writes = { "y" } }
rg.output "y"

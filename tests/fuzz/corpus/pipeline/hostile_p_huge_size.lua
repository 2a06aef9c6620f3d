local rg = require "rg"
rg.resource "r" { format = "rgba8", size = { 100000, 100000 } }
rg.pass "a" { kind = "clear", writes = { "r" } }
rg.output "r"

local rg = require "rg"
rg.resource "r" { format = "rgba8" }
rg.pass "a" { kind = "clear", writes = { "r" } }
rg.output "nothing"

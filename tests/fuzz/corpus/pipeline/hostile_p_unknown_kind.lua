local rg = require "rg"
rg.resource "r" { format = "rgba8" }
rg.pass "a" { kind = "fullscren", writes = { "r" } }
rg.output "r"

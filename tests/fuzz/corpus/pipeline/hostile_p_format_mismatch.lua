local rg = require "rg"
rg.resource "d" { format = "d32f" }
rg.resource "r" { format = "rgba8" }
rg.pass "z" { kind = "clear", writes = { "d" }, depth = 1 }
rg.pass "a" { kind = "copy", reads = { "d" }, writes = { "r" } }
rg.output "r"

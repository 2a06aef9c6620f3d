-- rg.output declared twice: the second replaces the first, whole, and the load says so.
local rg = require "rg"
rg.resource "first" { format = "rgba8" }
rg.resource "second" { format = "rgba8" }
rg.resource "linear" { format = "rgba16f" }
rg.pass "fill" { kind = "clear", writes = { "first", "second", "linear" } }
rg.output { display = "first", hdr = "linear" }
rg.output "second"

local rg = require "rg"
rg.param "x" { type = "number", default = 0.5, min = 0, max = 1 }
rg.resource "r" { format = "rgba8" }
rg.pass "a" { kind = "clear", writes = { "r" } }
rg.output "r"
function rg.frame(ctx) ctx.params.x = "a string" end

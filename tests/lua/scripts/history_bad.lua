local rg = require "rg"
rg.resource "ao" { format = "rg16f",
    history = { name = "ao_history", mip = 2 } }
rg.pass "fill" { kind = "clear", writes = { "ao" } }
rg.output "ao"

local rg = require "rg"
rg.resource "output" { format = "rgba16f" }
rg.pass "tonemap" { kind = "fullscreen", shadr = "post/tonemap.frag", writes = { "output" } }
rg.output "output"

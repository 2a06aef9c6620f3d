local rg = require "rg"
rg.param "curve" { type = "choice", default = "aces", choices = { "aces", "neutral" } }
rg.resource "output" { format = "rgba8" }
rg.pass "tonemap" { kind = "fullscreen", shader = "test/tint.frag", writes = { "output" },
    switches = { curv = "RG_CURVE" } }
rg.output "output"

local rg = require "rg"
rg.param "curve" { type = "choice", default = "aces", choices = { "aces", "neutral" } }
rg.resource "output" { format = "rgba8" }
rg.pass "tonemap" { kind = "fullscreen", shader = "test/tint.frag", writes = { "output" },
    switches = { curve = "2CURVE" } }
rg.output "output"

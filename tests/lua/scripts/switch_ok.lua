local rg = require "rg"
rg.param "curve" { type = "choice", default = "neutral", choices = { "aces", "neutral" } }
rg.param "dither" { type = "boolean", default = false }
rg.param "other" { type = "number", default = 1 }
rg.resource "output" { format = "rgba8" }
rg.pass "tonemap" { kind = "fullscreen", shader = "test/tint.frag", writes = { "output" },
    defines = { KEEP = true }, switches = { curve = "RG_CURVE", dither = "RG_DITHER" } }
rg.output "output"

-- A surface of uniform luminance through the camera and post chain (auto-exposure tests).
local rg = require "rg"
local post = require "post"
post.params { exposure_mode = "auto", dither = false, initial_ev100 = 10 }
post.exposure_state()
rg.param "luminance" { type = "number", default = 1000, min = 0, max = 1e12 }
rg.param "highlight" { type = "number", default = 0, min = 0, max = 1e12 }
rg.resource "hdr" { format = "rgba16f" }
rg.pass "emit" { kind = "fullscreen", shader = "test/emit.frag", reads = { { "exposure", as = "storage" } }, writes = { "hdr" } }
post.chain { input = "hdr", output = "display" }
rg.output { display = "display", hdr = "hdr", exposure = "exposure" }

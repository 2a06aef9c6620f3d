-- An aliased edge through the post chain, with and without FXAA.
local rg = require "rg"
local post = require "post"
post.params { exposure_mode = "manual", dither = false, aperture = 4, shutter = 1 / 60, iso = 100 }
post.exposure_state()
rg.param "luminance" { type = "number", default = 300, min = 0, max = 1e12 }
rg.resource "hdr" { format = "rgba16f" }
rg.pass "emit" { kind = "fullscreen", shader = "test/edge.frag", reads = { { "exposure", as = "storage" } }, writes = { "hdr" } }
post.chain { input = "hdr", output = "display", bloom_levels = 0 }
rg.output { display = "display", hdr = "hdr", exposure = "exposure" }

-- The default pipeline: Frostbite's render loop as a graph (seed 000 §3.2.2, lst:3; DESIGN §3).
-- It declares the material system (G-buffer layout of tbl:2, stencil classes, lighting paths,
-- the standard material) and the physical camera and post chain (seed 002 §5), and grows pass
-- by pass as the scene raster and lighting passes land. Until the scene raster pass exists the
-- HDR target shows a test card of `card_luminance` cd/m².
local rg = require "rg"
local post = require "post"
require "disney"

post.params { exposure_mode = "auto" }
post.exposure_state()
rg.param "card_luminance" { type = "number", default = 4000, min = 0, max = 1e9, doc = "test card luminance, cd/m²" }

rg.resource "card" { format = "rgba16f" }
rg.resource "hdr" { format = "rgba16f" }

rg.pass "card" { kind = "compute", shader = "test/pattern.comp", writes = { "card" }, bind = { pattern = "card" } }
rg.pass "present" {
    kind = "fullscreen", shader = "test/card_hdr.frag",
    reads = { "card", { "exposure", as = "storage" } }, writes = { "hdr" },
}

post.chain { input = "hdr", output = "display" }
rg.output { display = "display", hdr = "hdr", exposure = "exposure" }

local rg = require "rg"
require "disney"
-- Shares the standard material's id but would let decals blend less on its pixels.
rg.material "glossy" { id = 0, layout = "disney", path = "standard", decals = { "normal" } }

-- A material parameter named like a channel of its layout: refused at the declaration.
local rg = require "rg"
require "disney"
rg.material "toon" { id = 1, layout = "disney", path = "standard", surface = "materials/standard.glsl", params = { smoothness = 0.5 } }

-- A material's own textures: a name that is also its parameter, then four (at most three).
local rg = require "rg"
require "disney"
rg.material "toon" { id = 1, layout = "disney", path = "standard", surface = "materials/standard.glsl", params = { ink = 0.5 }, textures = { "ink" } }

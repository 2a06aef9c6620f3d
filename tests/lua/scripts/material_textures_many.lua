-- A material with four textures of its own: at most three.
local rg = require "rg"
require "disney"
rg.material "toon" { id = 1, layout = "disney", path = "standard", surface = "materials/standard.glsl", textures = { "a", "b", "c", "d" } }

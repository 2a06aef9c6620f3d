-- A material parameter named like a variable of the generated G-buffer shader.
local rg = require "rg"
require "disney"
rg.material "toon" { id = 1, layout = "disney", path = "standard", surface = "materials/standard.glsl", params = { uv0 = 1 } }

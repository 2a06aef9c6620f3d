require "pipelines.deferred"
local rg = require "rg"
rg.material "a-b" { id = 0, layout = "disney", stencil = "lit_standard", surface = "materials/standard.glsl" }
rg.material "a_b" { id = 0, layout = "disney", stencil = "lit_standard", surface = "materials/standard.glsl" }

require "pipelines.deferred"
local rg = require "rg"
rg.layout "ints" { { "GB0", "rgb10a2", { "normal:oct:20", "rim:unorm:10", "materialId:uint:2" } }, { "GB2", "r32ui", { "count:uint:32" } } }
rg.stencil "lit_ints" {}
rg.path "ints" { stencil = "lit_ints" }
rg.material "ints" { id = 3, layout = "ints", path = "ints", surface = "materials/standard.glsl" }

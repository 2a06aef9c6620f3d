local rg = require "rg"
require "disney"
rg.layout "toon" { { "GB0", "rgb10a2", { "normal:oct:20", "bands:unorm:10", "materialId:uint:2" } } }
rg.material "clearcoat" { id = 1, layout = "disney", path = "standard" }
rg.material "toon" { id = 1, layout = "toon", stencil = "lit_standard" }

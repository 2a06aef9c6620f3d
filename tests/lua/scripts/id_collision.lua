local rg = require "rg"
require "disney"
rg.layout "toon" { { "GB0", "rgb10a2", { "normal:oct:20", "bands:unorm:10", "spare:uint:2" } } }
rg.material "glossy" { layout = "disney", stencil = "lit_standard" }
rg.material "toon" { layout = "toon", stencil = "lit_standard" }

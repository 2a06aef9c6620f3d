local rg = require "rg"
require "disney"
rg.layout "toon" { { "GB0", "rgb10a2", { "normal:oct:20", "rim:unorm:10", "materialId:uint:2" } } }
-- The standard path's pass and shading decode the disney layout.
rg.material "toon" { id = 3, layout = "toon", path = "standard" }

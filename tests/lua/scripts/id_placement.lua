local rg = require "rg"
require "disney"
rg.layout "wide" {
    { "GB0", "rgba8", { "normal:oct:16", "smoothness:unorm:8", "materialId:uint:3", "spare:uint:5" } },
    { "GB1", "rgba8_srgb", { "baseColor:srgb:24", "rest:uint:8" } },
}
-- The standard material keeps materialId in 2 bits; this layout widens it to 3.
rg.material "wide" { id = 5, layout = "wide", stencil = "lit_standard" }

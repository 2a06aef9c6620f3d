local rg = require "rg"
require "disney"
rg.layout "wide" {
    { "GB0", "rgba8", { "normal:oct:16", "smoothness:unorm:8", "materialId:uint:3", "spare:uint:5" } },
    { "GB1", "rgba8_srgb", { "baseColor:srgb:24", "rest:uint:8" } },
}
-- Its materialId is 3 bits where the standard material's is 2: no matter, no pass decodes by it.
-- No lighting path, no stencil class: an identity whose low bits are 0.
rg.material "wide" { id = 5, layout = "wide" }
rg.resource "output" { format = "rgba8" }
rg.pass "fill" { kind = "clear", writes = { "output" } }

require "pipelines.deferred"
local rg = require "rg"
rg.layout "glow" {
    { "GB0", "rgb10a2", { "normal:oct:20", "smoothness:unorm:10", "materialId:uint:2" } },
    { "GB3", "rgba16f", { "albedo:float:16x3" } },
}
rg.stencil "lit_glow" {}
rg.path "glow" { stencil = "lit_glow" }
-- Decals would blend its colour, which lives in GB3: the decal pass writes GB0..GB2 only.
rg.material "glow" { id = 3, layout = "glow", path = "glow", channels = { baseColor = "albedo" }, decals = { "baseColor" }, surface = "glow.glsl" }

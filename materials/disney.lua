-- The standard (Disney) base material and its G-buffer, Frostbite seed 000 §3.2, tbl:2.
-- A pipeline pulls this in with `require "disney"`; game teams add materials the same way.
local rg = require "rg"

-- tbl:2. GB1 is sRGB so base colour keeps 8-bit precision where the eye needs it; the three
-- spare bits of GB1.A are declared so nothing is padded behind the script's back.
rg.layout "disney" {
    { "GB0", "rgb10a2",    { "normal:oct:20", "smoothness:unorm:10", "materialId:uint:2" } },
    { "GB1", "rgba8_srgb", { "baseColor:srgb:24", "materialData:uint:5", "normalExtra:uint:3" } },
    { "GB2", "rgba8",      { "reserved:unorm:8", "metalMask:unorm:8", "reflectance:unorm:8", "ao:unorm:8" } },
    { "GB3", "rgba16f",    { "emissive:float:16x3" } },
}

-- Pixels lit by the standard lighting path carry this stencil class (value allocated by rgraph).
rg.stencil "lit_standard" { doc = "standard Disney BRDF lighting" }
-- `shading` is the path's lighting function (rgShade over the layout's unpacked G-buffer): the
-- deferred lighting pass calls it on the G-buffer, the forward pass on blended surfaces.
rg.path "standard" { stencil = "lit_standard", shading = "standard_shading.glsl", doc = "Disney diffuse + GGX specular, seed 000 §3.1" }

-- materialId 0: BaseColor, Smoothness, MetalMask, Reflectance (f0 = 0.16 * reflectance^2), AO.
-- Decals blend MetalMask and Reflectance on the base material only (000 §3.3), beside the common
-- Normal, BaseColor and Smoothness every material takes by default.
rg.material "standard" {
    id = 0, layout = "disney", path = "standard", surface = "materials/standard.glsl",
    decals = { "normal", "baseColor", "smoothness", "metalMask", "reflectance" },
    doc = "the standard Disney base material, seed 000 §3.2.1",
}

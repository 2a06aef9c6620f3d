-- The disney layout's targets filled by a shader that includes the generated pack code.
local rg = require "rg"
require "disney"
for _, t in ipairs { { "GB0", "rgb10a2" }, { "GB1", "rgba8_srgb" }, { "GB2", "rgba8" }, { "GB3", "rgba16f" } } do
    rg.resource(t[1]) { format = t[2], export = true }
end
rg.pass "gbuffer" {
    kind = "fullscreen", shader = "test/gbuffer_fill.frag", writes = { "GB0", "GB1", "GB2", "GB3" },
    uniforms = { normal = { 0.3, -0.5, 0.8, 0 }, baseColor = { 0.8, 0.2, 0.05, 1 }, smoothness = 0.7,
                 metalMask = 1, reflectance = 0.5, ao = 0.9, materialId = 2 },
}
rg.output "GB3"

-- White furnace for image-based lighting: two rows of white spheres — dielectrics (reflectance
-- 0.5) in front, metals behind — from linear roughness 0 (left) to 1 (right), inside a uniform
-- environment of 1 nit and no light. Each sphere's centre faces the camera (N·V ≈ 1): there the
-- split sum is exact for a uniform probe, so the image must equal the BRDF's directional albedo
-- (tests/gpu/test_ibl.cpp).
local scene = require "scene"

local N = 5
for row, metal in ipairs({ 0, 1 }) do
  for i = 0, N - 1 do
    local name = string.format("ball_%d_%d", metal, i)
    scene.material(name) { base_color = { 1, 1, 1 }, smoothness = 1 - i / (N - 1), metal_mask = metal, reflectance = 0.5 }
    scene.sphere(name) { radius = 0.4, position = { (i - (N - 1) / 2) * 1.0, (row - 1.5) * 1.0, 0 }, material = name, segments = 48 }
  end
end

-- scene.args.environment = "sky": the clear sky (its sun 45° up, no sun light) instead, for the
-- comparison of the image-based lighting with the reference mode.
if scene.args.environment == "sky" then
  scene.environment "sky" { kind = "sky" }
else
  scene.environment "white" { kind = "color", color = { 1, 1, 1 }, intensity = 1, unit = "nits" }
end

-- Far away with a narrow field of view: nearly orthographic, so every sphere centre is seen head on.
scene.camera "main" { position = { 0, 0, 40 }, target = { 0, 0, 0 }, fov = 8.5, aperture = 2, shutter = 0.5, iso = 100 }

-- A glossy dielectric floor (smoothness 0.7, reflectance 0.5) under an area light: the specular
-- lobe looks at the light's representative point with the energy normalisation of seed 002
-- §4.7.5. tests/gpu/lights_fixture.h (withLight) swaps the scene.light line for each light type.
local scene = require "scene"
-- The base colour is sRGB code 128 exactly (0.2158605 linear), so GB1 stores it without rounding.
scene.material "glossy" { base_color = { 0.21586050011389923, 0.21586050011389923, 0.21586050011389923 }, metal_mask = 0, smoothness = 0.7, reflectance = 0.5 }
scene.plane "floor" { size = { 12, 12 }, material = "glossy" }
scene.camera "low" {
  position = { 0, 2.5, 4 }, target = { 0, 0, 0 }, fov = 60, near = 0.5, far = 100,
  aperture = 1.4, shutter = 1 / 15, iso = 100,  -- bright: the highlight's tails stay normal half floats
}
scene.light "area" { type = "sphere", intensity = 2000, unit = "lm", radius = 0.25, position = { 0, 1, -1 } }

-- A small scene with known material parameters, one object per material kind, for tests that
-- read parameters back (G-buffer contents, glTF round trips) rather than look at pictures.
local scene = require "scene"

scene.material "red_plastic" { base_color = { 0.8, 0.05, 0.05 }, smoothness = 0.7, reflectance = 0.5 }
scene.material "gold" { base_color = { 1.0, 0.766, 0.336 }, metal_mask = 1, smoothness = 0.9 }
scene.material "chalk" { base_color = { 0.9, 0.9, 0.88 }, smoothness = 0.0, reflectance = 0.35, ao = 0.8 }
-- Two-colour base material (seed 000 tbl:3): diffuse colour and f0 given directly.
scene.material "rust" { model = "two_colour", diffuse_color = { 0.30, 0.12, 0.05 }, f0 = { 0.35, 0.25, 0.2 }, smoothness = 0.3 }
-- 500 nits: a lit sign.
scene.material "sign" { base_color = { 0.1, 0.1, 0.1 }, emissive = { 500, 250, 50 } }
-- A game-team material: its parameters ride along in Material::extra.
scene.material "car_paint" {
  model = "clear_coat", base_color = { 0.05, 0.1, 0.6 }, smoothness = 0.6,
  params = { coatStrength = 1.0, coatSmoothness = 0.95 },
}
scene.material "glass" { base_color = { 0.9, 0.95, 1.0 }, smoothness = 1, alpha = "blend", opacity = 0.3, double_sided = true }
scene.material "ground" { base_color = { 0.5, 0.5, 0.5 }, smoothness = 0.5 }

scene.sphere "red_plastic" { radius = 0.5, position = { -3, 0.5, 0 }, material = "red_plastic" }
scene.sphere "gold" { radius = 0.5, position = { -1.8, 0.5, 0 }, material = "gold" }
scene.sphere "chalk" { radius = 0.5, position = { -0.6, 0.5, 0 }, material = "chalk" }
scene.sphere "rust" { radius = 0.5, position = { 0.6, 0.5, 0 }, material = "rust" }
scene.box "sign" { size = { 0.8, 0.8, 0.1 }, position = { 1.8, 0.5, 0 }, material = "sign" }
scene.sphere "car_paint" { radius = 0.5, position = { 3.0, 0.5, 0 }, material = "car_paint" }
scene.plane "glass" { size = { 1, 1 }, position = { 0, 0.5, 1.2 }, rotation = { 90, 0, 0 }, material = "glass" }
scene.plane "ground" { size = { 10, 6 }, material = "ground" }

scene.light "sun" { type = "sun", intensity = 10000, unit = "lux", direction = { 0.3, -1, -0.5 } }
scene.light "bulb" { type = "point", intensity = 100, unit = "cd", position = { 0, 2, 1.5 }, color = { 1, 0.9, 0.8 } }
scene.light "softbox" {
  type = "rect", intensity = 3000, unit = "nits", position = { 0, 2.5, -2 }, target = { 0, 0, 0 },
  width = 1.0, height = 0.6,
}

-- f/5.6, 1/125 s, ISO 100: EV100 ~12, for ~10 000 lux.
scene.camera "main" { position = { 0, 2, 6 }, target = { 0, 0.5, 0 }, fov = 35, aperture = 5.6, shutter = 1 / 125, iso = 100 }
scene.environment "sky" { kind = "sky" }

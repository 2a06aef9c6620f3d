-- Ranged lights of every type in the tiles' lists (point, spot with an IES profile, sphere, disk,
-- rect, tube) beside a sun, over a floor with a glossy ball and a metal box, and a blended pane
-- lit in the forward pass from its froxels: what the light loops read of every light's fields
-- (tests/gpu/test_lights_tiles.cpp compares the lights read through the texel buffer with the
-- storage block's). Ranges of 3 m keep them out of the unrolled global lights.
local scene = require "scene"
scene.material "floor" { base_color = { 0.6, 0.6, 0.6 }, smoothness = 0.5 }
scene.material "glossy" { base_color = { 0.2, 0.4, 0.8 }, smoothness = 0.8 }
scene.material "metal" { base_color = { 0.9, 0.7, 0.3 }, metal_mask = 1, smoothness = 0.6 }
scene.material "glass" { base_color = { 0.9, 0.95, 1.0 }, smoothness = 0.9, alpha = "blend", opacity = 0.4, double_sided = true }
scene.plane "floor" { size = { 10, 10 }, material = "floor" }
scene.sphere "ball" { radius = 0.5, position = { -0.7, 0.5, 0 }, material = "glossy" }
scene.box "box" { size = { 0.8, 0.8, 0.8 }, position = { 0.7, 0.4, 0 }, material = "metal" }
scene.box "pane" { size = { 3, 0.02, 1 }, position = { 0, 0.15, 1.2 }, material = "glass" }
scene.camera "main" { position = { 0, 3, 4 }, target = { 0, 0.3, 0 }, fov = 45, aperture = 4, shutter = 1 / 60, iso = 100 }
scene.light "sun" { type = "sun", intensity = 200, unit = "lux", direction = { -0.4, -0.8, -0.45 } }
scene.light "bulb" { type = "point", intensity = 800, unit = "lm", position = { 1.5, 1.2, 1.0 }, range = 3 }
scene.light "spot" { type = "spot", intensity = 1200, unit = "lm", position = { -1.5, 2.0, 1.0 }, target = { -0.5, 0, -0.2 },
                     inner_angle = 20, outer_angle = 35, ies = "../../unit/ies/bilateral_1991.ies", range = 3 }
scene.light "globe" { type = "sphere", intensity = 600, unit = "lm", radius = 0.15, position = { 1.4, 0.8, -0.6 }, range = 3 }
scene.light "disk" { type = "disk", intensity = 900, unit = "lm", radius = 0.2, position = { -1.2, 1.0, -1.0 }, direction = { 0.3, -1, 0.4 }, range = 3 }
scene.light "panel" { type = "rect", intensity = 900, unit = "lm", width = 0.6, height = 0.3, position = { 0, 1.5, -1.2 },
                      direction = { 0, -1, 0.3 }, up = { 0, 0, 1 }, range = 3 }
scene.light "tube" { type = "tube", intensity = 700, unit = "lm", radius = 0.04, length = 0.8, position = { 0.2, 0.9, 1.6 },
                     direction = { 1, 0, 0 }, range = 3 }

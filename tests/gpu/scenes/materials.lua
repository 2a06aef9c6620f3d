-- One object per pipeline material under a sun: standard, clear coat, foliage; for the tests of
-- the material system (known parameters, read back from the G-buffer).
local scene = require "scene"
scene.material "floor" { base_color = { 0.2, 0.2, 0.2 }, smoothness = 0.3 }
scene.plane "floor" { size = { 8, 8 }, material = "floor" }
scene.material "red" { base_color = { 0.8, 0.05, 0.05 }, smoothness = 0.6, metal_mask = 0, reflectance = 0.5 }
scene.sphere "standard" { radius = 0.5, position = { -1.2, 0.5, 0 }, material = "red" }
scene.material "coated" { model = "clear_coat", base_color = { 0.8, 0.05, 0.05 }, smoothness = 0.6,
                          params = { coatSmoothness = 0.95, coatStrength = 1.0 } }
scene.sphere "coated" { radius = 0.5, position = { 0, 0.5, 0 }, material = "coated" }
scene.material "leaf" { model = "foliage", base_color = { 0.1, 0.5, 0.05 }, smoothness = 0.4, double_sided = true }
scene.box "bush" { size = { 0.8, 0.8, 0.8 }, position = { 1.2, 0.4, 0 }, material = "leaf" }
scene.light "sun" { type = "sun", intensity = 50000, unit = "lux", direction = { -0.3, -0.8, -0.5 } }
scene.camera "main" { position = { 0, 1.2, 3.4 }, target = { 0, 0.45, 0 }, fov = 45, aperture = 16, shutter = 1 / 125, iso = 100 }
scene.material "glass" { base_color = { 0.2, 0.4, 0.9 }, smoothness = 0.9, alpha = "blend", opacity = 0.35 }
scene.box "pane" { size = { 0.9, 0.9, 0.02 }, position = { -0.6, 0.5, 1.0 }, material = "glass" }
-- A decal on the floor and across the clear-coat sphere: red, glossy, metal where it may be.
scene.decal "stain" { position = { 0.35, 0.3, 0.6 }, size = { 1.0, 1.2, 1.0 }, base_color = { 0.9, 0.1, 0.1 },
                      smoothness = 0.9, metal_mask = 1, opacity = 0.8 }
-- The two-colour base material (tbl:3), and a decal over its front: base colour blends into its
-- diffuse colour; metal mask and reflectance (base material only) leave its f0 alone.
scene.material "oxide" { model = "two_colour", diffuse_color = { 0.30, 0.12, 0.05 }, f0 = { 0.35, 0.25, 0.20 }, smoothness = 0.5 }
scene.sphere "oxide" { radius = 0.5, position = { -2.3, 0.5, -0.3 }, material = "oxide" }
scene.decal "patch" { position = { -2.3, 0.5, 0.2 }, size = { 0.5, 0.5, 0.5 }, base_color = { 0.1, 0.2, 0.8 },
                      smoothness = 0.9, metal_mask = 1, reflectance = 1, opacity = 0.5 }
-- The clear sky of that sun: the distant probe lighting every material path (and the forward pane).
scene.environment "sky" { kind = "sky" }

-- Noon in full sun: 100 000 lux (seed 000 tbl:11's order of magnitude), a white floor and a
-- glossy steel sphere that reflects the sun; the camera is auto-exposed (pre-exposure keeps the
-- half-float targets finite).
local scene = require "scene"
scene.material "white" { base_color = { 0.9, 0.9, 0.9 }, smoothness = 0.2 }
scene.plane "floor" { size = { 20, 20 }, material = "white" }
scene.material "steel" { base_color = { 0.95, 0.95, 0.95 }, metal_mask = 1, smoothness = 0.75 }
scene.sphere "ball" { radius = 0.6, position = { 0, 0.6, 0 }, material = "steel", segments = 48 }
scene.light "sun" { type = "sun", intensity = 100000, unit = "lux", direction = { -0.2, -0.9, -0.35 } }
-- The clear sky of that sun (Preetham, scaled to its lux): the probe that lights the shade.
scene.environment "sky" { kind = "sky" }
scene.camera "main" { position = { 0, 1.6, 4 }, target = { 0, 0.5, 0 }, fov = 45, aperture = 16, shutter = 1 / 125, iso = 100 }

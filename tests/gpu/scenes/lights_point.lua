-- A white floor (base colour 1, metal mask 0, smoothness 0, reflectance 0.5) under a 625 lm point
-- light, seen from straight above: seed 000 tbl:10's bulb. At 1 m, 0.5 m, 0.25 m and 0.1 m above
-- the floor it gives 49.7, 198.9, 795.8 and 4973.6 lux below it (tests/gpu/test_lights.cpp moves
-- the light by rewriting the scene.light line).
local scene = require "scene"
scene.material "white" { base_color = { 1, 1, 1 }, metal_mask = 0, smoothness = 0 }
scene.plane "floor" { size = { 12, 12 }, material = "white" }
scene.camera "top" {
  position = { 0, 5, 0 }, target = { 0, 0, 0 }, up = { 0, 0, -1 }, fov = 60, near = 0.5, far = 100,
  aperture = 2.8, shutter = 1 / 60, iso = 100,
}
scene.light "bulb" { type = "point", intensity = 625, unit = "lm", position = { 0, 1, 0 } }

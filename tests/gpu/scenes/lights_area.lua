-- A white, purely diffuse floor (reflectance 0: no specular lobe at all, so a pixel is the Disney
-- diffuse BRDF times the illuminance) under one area light, seen from straight above. This one is a
-- 0.5 m sphere of 2000 lm whose bottom dips below the floor, so the points around it see it cross
-- their horizon (seed 000 lst:10). tests/gpu/lights_fixture.h swaps the scene.light line for discs,
-- rectangles and tubes, and for the same sphere in nits and EV100.
local scene = require "scene"
scene.material "white" { base_color = { 1, 1, 1 }, metal_mask = 0, smoothness = 0, reflectance = 0 }
scene.plane "floor" { size = { 12, 12 }, material = "white" }
scene.camera "top" {
  position = { 0, 5, 0 }, target = { 0, 0, 0 }, up = { 0, 0, -1 }, fov = 60, near = 0.5, far = 100,
  aperture = 2.8, shutter = 1 / 60, iso = 100,
}
scene.light "area" { type = "sphere", intensity = 2000, unit = "lm", radius = 0.5, position = { 0, 0.4, 0 } }

-- A full summer sun, 100 000 lux perpendicular to its rays (seed 000 tbl:11), on the white floor
-- and on a glossy ball whose normals face every way (the lst:6 disk's closest point must stay
-- finite where the reflection vector meets the sun or points away from it).
local scene = require "scene"
scene.material "white" { base_color = { 1, 1, 1 }, metal_mask = 0, smoothness = 0 }
scene.plane "floor" { size = { 12, 12 }, material = "white" }
scene.material "glossy" { base_color = { 0.9, 0.6, 0.3 }, metal_mask = 1, smoothness = 0.8 }
scene.sphere "ball" { radius = 0.6, position = { 1.2, 0.6, 0.8 }, material = "glossy", segments = 64 }
scene.camera "top" {
  position = { 0, 5, 0 }, target = { 0, 0, 0 }, up = { 0, 0, -1 }, fov = 60, near = 0.5, far = 100,
  aperture = 2.8, shutter = 1 / 60, iso = 100,
}
scene.light "sun" { type = "sun", intensity = 100000, unit = "lux", direction = { -0.3, -0.8, -0.5 } }

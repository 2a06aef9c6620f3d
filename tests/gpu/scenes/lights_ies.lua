-- A spot light pointing down, masked by an asymmetric IES profile (a forward-throw luminaire:
-- 470 cd at the nadir, 409.7 cd at 30° towards horizontal angle 0°, 149.9 cd at 30° towards 180°),
-- over the white diffuse floor. The profile's horizontal angle 0° lies along +z here (the spot
-- points straight down, parallel to its default up; see passes/gpu_scene.h convertLights).
local scene = require "scene"
scene.material "white" { base_color = { 1, 1, 1 }, metal_mask = 0, smoothness = 0, reflectance = 0 }
scene.plane "floor" { size = { 12, 12 }, material = "white" }
scene.camera "top" {
  position = { 0, 5, 0 }, target = { 0, 0, 0 }, up = { 0, 0, -1 }, fov = 60, near = 0.5, far = 100,
  aperture = 2.8, shutter = 1 / 60, iso = 100,
}
scene.light "washer" {
  type = "spot", intensity = 1000, unit = "lm", position = { 0, 1.5, 0 }, direction = { 0, -1, 0 },
  inner_angle = 70, outer_angle = 85, ies = "../../unit/ies/bilateral_1991.ies",
}

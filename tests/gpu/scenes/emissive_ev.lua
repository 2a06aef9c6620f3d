-- Emission relative to the exposure (a material's emissive_unit = "ev", seed 002 §5.1.3): a black,
-- non-reflective sphere emitting (0.5, 0.25, 0.125) at EC +1 in the centre of the view, drawn by
-- the G-buffer pass, or with scene.args.forward = 1 a blended one of EC 0 emitting (1, 1, 1), drawn
-- by the forward pass; a floor under the sun. scene.args.aperture sets the camera's f-number.
local scene = require "scene"
scene.material "floor" { base_color = { 0.5, 0.5, 0.5 }, smoothness = 0.2 }
scene.plane "floor" { size = { 20, 20 }, material = "floor" }
if scene.args.forward == 1 then
  scene.material "lamp" { base_color = { 0, 0, 0 }, metal_mask = 0, reflectance = 0, smoothness = 0,
                          emissive = { 1, 1, 1 }, emissive_unit = "ev", alpha = "blend", opacity = 1 }
else
  scene.material "lamp" { base_color = { 0, 0, 0 }, metal_mask = 0, reflectance = 0, smoothness = 0,
                          emissive = { 0.5, 0.25, 0.125 }, emissive_unit = "ev", emissive_ec = 1 }
end
scene.sphere "lamp" { radius = 0.5, position = { 0, 0.6, 0 }, material = "lamp" }
scene.light "sun" { type = "sun", intensity = 50000, unit = "lux", direction = { -0.4, -0.8, -0.45 } }
scene.camera "main" { position = { 0, 0.6, 3 }, target = { 0, 0.6, 0 }, fov = 30,
                      aperture = scene.args.aperture or 16, shutter = 1 / 125, iso = 100 }

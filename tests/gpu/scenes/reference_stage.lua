-- The stage of the reference-mode scenes (reference_*.lua, `require "reference_stage"`): a white,
-- purely diffuse floor (reflectance 0: no specular lobe, so floor pixels measure only the diffuse
-- approximation) and four spheres — rough and glossy dielectrics, a rough gold and a near-mirror
-- chrome — seen from the front. Each scene adds one light.
local scene = require "scene"
scene.material "floor" { base_color = { 0.8, 0.8, 0.8 }, metal_mask = 0, smoothness = 0, reflectance = 0 }
scene.material "rough" { base_color = { 0.8, 0.2, 0.2 }, metal_mask = 0, smoothness = 0.3 }
scene.material "glossy" { base_color = { 0.2, 0.4, 0.8 }, metal_mask = 0, smoothness = 0.8 }
scene.material "gold" { base_color = { 1.0, 0.78, 0.34 }, metal_mask = 1, smoothness = 0.6 }
scene.material "chrome" { base_color = { 0.55, 0.55, 0.55 }, metal_mask = 1, smoothness = 0.95 }
scene.plane "floor" { size = { 12, 12 }, material = "floor" }
scene.sphere "rough" { radius = 0.4, position = { -1.5, 0.4, 0 }, material = "rough", segments = 64 }
scene.sphere "glossy" { radius = 0.4, position = { -0.5, 0.4, 0 }, material = "glossy", segments = 64 }
scene.sphere "gold" { radius = 0.4, position = { 0.5, 0.4, 0 }, material = "gold", segments = 64 }
scene.sphere "chrome" { radius = 0.4, position = { 1.5, 0.4, 0 }, material = "chrome", segments = 64 }
scene.camera "front" {
  position = { 0, 1.4, 3.2 }, target = { 0, 0.35, 0 }, fov = 45, near = 0.1, far = 100,
  aperture = 2.8, shutter = 1 / 60, iso = 100,
}

-- Reference-mode test scene (scripts/pipelines/reference.lua): the game team's clear-coat material
-- (materials/clearcoat.lua, materialId 1: the standard base under a second GGX lobe) next to the
-- standard material, on a white diffuse floor, under ONE sphere light. The reference integrates the
-- coat's BRDF per direction (base · (1 − Fc) + coat lobe); deferred.lua lights it in
-- lighting_clearcoat with two representative points. Swap the light for a point light and the two
-- renders must agree exactly (delta light: no approximation on either side).
local scene = require "scene"
scene.material "floor" { base_color = { 0.8, 0.8, 0.8 }, metal_mask = 0, smoothness = 0, reflectance = 0 }
scene.material "plain" { base_color = { 0.8, 0.05, 0.05 }, metal_mask = 0, smoothness = 0.6 }
scene.material "coated" { model = "clear_coat", base_color = { 0.8, 0.05, 0.05 }, smoothness = 0.5,
                          params = { coatSmoothness = 0.95, coatStrength = 1.0 } }
scene.material "coated_metal" { model = "clear_coat", base_color = { 0.9, 0.6, 0.3 }, metal_mask = 1, smoothness = 0.3,
                                params = { coatSmoothness = 0.8, coatStrength = 0.7 } }
scene.plane "floor" { size = { 12, 12 }, material = "floor" }
scene.sphere "plain" { radius = 0.4, position = { -1.0, 0.4, 0 }, material = "plain", segments = 64 }
scene.sphere "coated" { radius = 0.4, position = { 0, 0.4, 0 }, material = "coated", segments = 64 }
scene.sphere "coated_metal" { radius = 0.4, position = { 1.0, 0.4, 0 }, material = "coated_metal", segments = 64 }
scene.camera "front" {
  position = { 0, 1.4, 3.2 }, target = { 0, 0.35, 0 }, fov = 45, near = 0.1, far = 100,
  aperture = 2.8, shutter = 1 / 60, iso = 100,
}
scene.light "key" { type = "sphere", intensity = 3000, unit = "lm", radius = 0.3, position = { 0, 1.6, 1.0 } }

-- White furnace: a white, non-metallic sphere inside a uniform white environment of 1 nit and
-- no other light. An energy-conserving BRDF that also preserves energy (no loss) returns the
-- environment's luminance everywhere on the sphere: the sphere vanishes into the background.
-- Tests read the rendered luminance and compare it with 1 nit.
local scene = require "scene"

scene.material "white" { base_color = { 1, 1, 1 }, smoothness = 0.5, metal_mask = 0, reflectance = 0.5 }
scene.sphere "ball" { radius = 1, position = { 0, 0, 0 }, material = "white", segments = 96 }

scene.environment "white" { kind = "color", color = { 1, 1, 1 }, intensity = 1, unit = "nits" }

-- EV100 = log2(L * S / K) = log2(1 * 100 / 12.5) = 3 for 1 nit: N^2 / t = 8, e.g. f/2 at 1/2 s.
scene.camera "main" { position = { 0, 0, 4 }, target = { 0, 0, 0 }, fov = 40, aperture = 2, shutter = 0.5, iso = 100 }

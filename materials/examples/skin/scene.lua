-- The skin package's example scene: three skin spheres under a low sun — no scatter (Lambert), the
-- default scatter colour, the broadest in every channel — beside a standard sphere of the same
-- colour, on a standard floor; a decal paints a stripe across the middle skin sphere.
local scene = require "scene"
scene.material "floor" { base_color = { 0.5, 0.5, 0.5 }, smoothness = 0.3 }
scene.plane "floor" { size = { 8, 8 }, material = "floor" }
local tone = { 0.8, 0.55, 0.45 }
scene.material "lambert_skin" { model = "skin", base_color = tone, smoothness = 0.45, params = { scatterR = 0, scatterG = 0, scatterB = 0 } }
scene.material "skin" { model = "skin", base_color = tone, smoothness = 0.45 }
scene.material "broad_skin" { model = "skin", base_color = tone, smoothness = 0.45, params = { scatterR = 1, scatterG = 1, scatterB = 1 } }
scene.material "standard" { base_color = tone, smoothness = 0.45 }
scene.sphere "lambert" { radius = 0.4, position = { -1.35, 0.4, 0 }, material = "lambert_skin" }
scene.sphere "skin" { radius = 0.4, position = { -0.45, 0.4, 0 }, material = "skin" }
scene.sphere "broad" { radius = 0.4, position = { 0.45, 0.4, 0 }, material = "broad_skin" }
scene.sphere "standard" { radius = 0.4, position = { 1.35, 0.4, 0 }, material = "standard" }
scene.decal "stripe" { position = { -0.45, 0.4, 0.35 }, size = { 0.9, 0.12, 0.4 }, base_color = { 0.15, 0.2, 0.5 }, opacity = 0.8 }
scene.light "sun" { type = "sun", intensity = 50000, unit = "lux", direction = { -0.9, -0.3, -0.3 } }
scene.environment "sky" { kind = "sky" }
scene.camera "main" { position = { 0, 1.1, 3.6 }, target = { 0, 0.4, 0 }, fov = 45, aperture = 16, shutter = 1 / 125, iso = 100 }

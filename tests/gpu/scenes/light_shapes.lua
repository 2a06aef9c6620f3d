-- The area lights' emissive shapes (seed 002 §4.8; tests/gpu/test_light_shapes.cpp): a sphere, a
-- disk and a rect facing the camera and a vertical tube, 2000 lm each, over a floor, no
-- environment. scene.args: visible (0 hides the shapes), smoothness (the floor's, default 0.3),
-- shadow (1: every light casts its shadow map, within 20 m), probe (1: a sphere probe of radius
-- 6 m at (0, 1, 2)).
local scene = require "scene"
local visible = tostring(scene.args.visible) ~= "0"
local shadow = tostring(scene.args.shadow) == "1"
local range = shadow and 20 or 0
scene.material "floor" { base_color = { 0.5, 0.5, 0.5 }, smoothness = tonumber(scene.args.smoothness) or 0.3 }
scene.plane "floor" { size = { 12, 8 }, material = "floor" }
scene.light "ball" { type = "sphere", intensity = 2000, unit = "lm", radius = 0.2, position = { -2.4, 1.0, 0 },
                     visible = visible, shadow = shadow, range = range }
scene.light "disk" { type = "disk", intensity = 2000, unit = "lm", radius = 0.3, position = { -0.8, 1.0, 0 },
                     direction = { 0, 0, 1 }, visible = visible, shadow = shadow, range = range }
scene.light "rect" { type = "rect", intensity = 2000, unit = "lm", width = 0.6, height = 0.3, position = { 0.8, 1.0, 0 },
                     direction = { 0, 0, 1 }, up = { 0, 1, 0 }, visible = visible, shadow = shadow, range = range }
scene.light "tube" { type = "tube", intensity = 2000, unit = "lm", radius = 0.05, length = 0.8, position = { 2.4, 1.0, 0 },
                     direction = { 0, 1, 0 }, visible = visible, shadow = shadow, range = range }
scene.camera "main" { position = { 0, 1.6, 5 }, target = { 0, 0.8, 0 }, fov = 45, aperture = 4, shutter = 1 / 60, iso = 400 }
if tostring(scene.args.probe) == "1" then
  scene.probe "front" { position = { 0, 1, 2 }, radius = 6 }
end

-- A glossy metal floor under an area light that casts shadows, seen so that the light's
-- reflection (its highlight) lies at the origin; scene.args.box = 0 leaves out the box that stands
-- on the light's path to that point (in front of the highlight, out of the camera's way).
-- scene.args.light: "sphere" (default), "disk", "rect" or "tube". tests/gpu/test_shadows.cpp
-- renders it under both area-light models (seed 002 §4.10.4: the specular is shadowed too).
local scene = require "scene"
scene.material "floor" { base_color = { 0.9, 0.9, 0.9 }, metal_mask = 1, smoothness = 0.8 }
scene.plane "floor" { size = { 12, 12 }, material = "floor" }
if scene.args.box ~= 0 then
  scene.material "box" { base_color = { 0.5, 0.5, 0.5 }, smoothness = 0.3 }
  scene.box "box" { size = { 0.6, 0.3, 0.4 }, position = { 0, 0.75, -1.5 }, material = "box" }
end
local kind = scene.args.light or "sphere"
local at, towards = { 0, 1.5, -3 }, { 0, 0, 0 }
if kind == "sphere" then
  scene.light "area" { type = "sphere", radius = 0.15, intensity = 3000, unit = "lm", position = at, range = 20, shadow = true }
elseif kind == "disk" then
  scene.light "area" { type = "disk", radius = 0.15, intensity = 3000, unit = "lm", position = at, target = towards, range = 20, shadow = true }
elseif kind == "rect" then
  scene.light "area" { type = "rect", width = 0.3, height = 0.2, intensity = 3000, unit = "lm", position = at, target = towards, range = 20,
                       shadow = true }
elseif kind == "tube" then
  scene.light "area" { type = "tube", radius = 0.03, length = 0.3, intensity = 3000, unit = "lm", position = at, target = towards,
                       range = 20, shadow = true }
else
  error("scene.args.light: expected 'sphere', 'disk', 'rect' or 'tube'")
end
scene.camera "view" { position = { 0, 1.5, 3 }, target = { 0, 0, 0 }, fov = 40, near = 0.1, far = 50,
                      aperture = 2, shutter = 1 / 30, iso = 100 }

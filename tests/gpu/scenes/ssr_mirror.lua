-- Screen-space reflection test: a mirror floor (metal, smoothness 1) under a red box, an oblique
-- camera, the clear sky as the distant probe, no sun (no shadows in the way). scene.args.box = 0
-- leaves the floor alone; scene.args.floor = "clear_coat" or "two_colour" makes the mirror of that
-- pipeline material (a metal base under a smooth coat; an f0 colour of 0.95), lit by its own path.
local scene = require "scene"
local floor = scene.args.floor or "standard"
if floor == "clear_coat" then
  scene.material "mirror" { model = "clear_coat", base_color = { 0.95, 0.95, 0.95 }, metal_mask = 1, smoothness = 1,
                            params = { coatSmoothness = 1, coatStrength = 1 } }
elseif floor == "two_colour" then
  scene.material "mirror" { model = "two_colour", diffuse_color = { 0, 0, 0 }, f0 = { 0.95, 0.95, 0.95 }, smoothness = 1 }
else
  assert(floor == "standard", "scene.args.floor: expected standard, clear_coat or two_colour")
  scene.material "mirror" { base_color = { 0.95, 0.95, 0.95 }, metal_mask = 1, smoothness = 1 }
end
scene.plane "floor" { size = { 20, 20 }, material = "mirror" }
if scene.args.box ~= 0 then
  scene.material "red" { base_color = { 0.8, 0.05, 0.05 }, smoothness = 0.3, emissive = { 200, 10, 10 } }
  scene.box "box" { size = { 1, 1, 1 }, position = { 0, 0.5, -2 }, material = "red" }
end
scene.environment "sky" { kind = "sky" }
scene.camera "main" { position = { 0, 2, 6 }, target = { 0, 0, 0 }, fov = 40, aperture = 4, shutter = 1 / 60, iso = 100 }

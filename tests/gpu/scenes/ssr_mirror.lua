-- Screen-space reflection test: a mirror floor (metal, smoothness 1) under a red box, an oblique
-- camera, the clear sky as the distant probe, no sun (no shadows in the way). scene.args.box = 0
-- leaves the floor alone.
local scene = require "scene"
scene.material "mirror" { base_color = { 0.95, 0.95, 0.95 }, metal_mask = 1, smoothness = 1 }
scene.plane "floor" { size = { 20, 20 }, material = "mirror" }
if scene.args.box ~= 0 then
  scene.material "red" { base_color = { 0.8, 0.05, 0.05 }, smoothness = 0.3, emissive = { 200, 10, 10 } }
  scene.box "box" { size = { 1, 1, 1 }, position = { 0, 0.5, -2 }, material = "red" }
end
scene.environment "sky" { kind = "sky" }
scene.camera "main" { position = { 0, 2, 6 }, target = { 0, 0, 0 }, fov = 40, aperture = 4, shutter = 1 / 60, iso = 100 }

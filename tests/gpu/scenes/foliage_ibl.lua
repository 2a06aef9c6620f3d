-- A box of foliage under the clear sky alone (no light), its front face towards the camera; with
-- scene.args.model = "black" a standard box instead with no diffuse colour and the foliage's
-- specular (reflectance 0.35 as foliage_reflectance, the same smoothness): what the distant probe
-- adds besides the diffuse (tests/gpu/test_scene_render.cpp, seed 000 lst:3).
local scene = require "scene"
if scene.args.model == "black" then
  scene.material "leaf" { base_color = { 0, 0, 0 }, smoothness = 0.4, reflectance = 0.35 }
else
  scene.material "leaf" { model = "foliage", base_color = { 0.1, 0.5, 0.05 }, smoothness = 0.4 }
end
scene.box "bush" { size = { 1, 1, 1 }, position = { 0, 0, 0 }, material = "leaf" }
scene.environment "sky" { kind = "sky" }
scene.camera "main" { position = { 0, 0, 3 }, target = { 0, 0, 0 }, fov = 30, aperture = 16, shutter = 1 / 125, iso = 100 }

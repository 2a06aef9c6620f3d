-- Moving objects by their numbers (tests/gpu/test_motion.cpp), seen by an orthographic camera 4 m
-- high from +Z: a wall of 10 nits behind, and in front of it
--   `slider`  a box gliding along +x at 4 m/s between the path's middle keys (t = 0.25 .. 0.5 s:
--             Catmull-Rom tangents from evenly spaced keys are the constant speed there), turned
--             about Z as it goes (90° a second);
--   `glass`   a blended pane rising along +y at 2 m/s over the same span (the forward pass's motion);
--   `post`    a box that stands still.
-- scene.args.perspective = 1: the same from a perspective camera, 40° high, 10 m away.
-- scene.args.checker = FILE: the slider's emission times that image (the TAA test's checkerboard).
local scene = require "scene"

scene.environment "black" { kind = "color", color = { 1, 1, 1 }, intensity = 0, unit = "nits" }
scene.material "wall" { base_color = { 0, 0, 0 }, emissive = { 10, 10, 10 } }
scene.box "wall" { size = { 8, 8, 0.1 }, position = { 0, 0, -2 }, material = "wall" }

scene.material "slider" { base_color = { 0, 0, 0 }, emissive = { 40, 5, 5 }, emissive_map = scene.args.checker }
scene.box "slider" { size = { 0.5, 0.5, 0.5 }, position = { -1.5, 0.6, 0 }, material = "slider",
  path = {
    { time = 0.00, position = { -1.5, 0.6, 0 }, rotation = { 0, 0, 0 } },
    { time = 0.25, position = { -0.5, 0.6, 0 }, rotation = { 0, 0, 22.5 } },
    { time = 0.50, position = { 0.5, 0.6, 0 }, rotation = { 0, 0, 45 } },
    { time = 0.75, position = { 1.5, 0.6, 0 }, rotation = { 0, 0, 67.5 } },
  } }

scene.material "glass" { base_color = { 0, 0, 0 }, emissive = { 5, 40, 5 }, opacity = 0.5, alpha = "blend" }
scene.box "glass" { size = { 0.6, 0.4, 0.02 }, position = { 0.8, -1.3, 0.5 }, material = "glass",
  path = {
    { time = 0.00, position = { 0.8, -1.3, 0.5 } },
    { time = 0.25, position = { 0.8, -0.8, 0.5 } },
    { time = 0.50, position = { 0.8, -0.3, 0.5 } },
    { time = 0.75, position = { 0.8, 0.2, 0.5 } },
  } }

scene.material "post" { base_color = { 0, 0, 0 }, emissive = { 5, 5, 40 } }
scene.box "post" { size = { 0.4, 0.4, 0.4 }, position = { -1.2, -1.0, 0 }, material = "post" }

if scene.args.perspective == 1 then
  scene.camera "main" { position = { 0, 0, 10 }, target = { 0, 0, 0 }, fov = 40, aperture = 2, shutter = 0.5, iso = 100 }
else
  scene.camera "main" { position = { 0, 0, 10 }, target = { 0, 0, 0 }, height = 4, aperture = 2, shutter = 0.5, iso = 100 }
end

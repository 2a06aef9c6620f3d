-- Local light probe tests (scripts/probes.lua, lib/probes.glsl; seed 002 §4.9.5, appendix F): a
-- mirror floor under a red (emissive) box, the clear sky as the distant probe, no sun.
-- scene.args.probes:
--   "none" (default)  no local probe;
--   "one"             a box probe in front of the box (capture point 0.5 m from its face), its
--                     proxy x ∈ [−2, 2], y ∈ [−1, 2], z ∈ [−4, 2];
--   "priority"        two sphere probes of radius 3 at x = ∓1.5, 1 m up: "right" has priority 2,
--                     "left" priority 1 (the floor: discs of radius 2.83 around x = ∓1.5);
--   "size"            two sphere probes of the same priority: "big" (radius 4 at x = −1) and
--                     "small" (radius 2 at x = 1; its floor disc has radius 1.73);
--   "influence"       one sphere probe of radius 1, 1 m up, reflecting within 3 m (its floor disc:
--                     radius 2.83);
--   "front_first", "back_first"  a green emissive wall behind the box (z = −6) and two sphere
--                     probes of radius 6 that both hold the box's mirror image: "front" (in front
--                     of the box: it sees the red box there) and "back" (behind the box: it sees the
--                     green wall there); the first named has the higher priority.
-- Cameras: "main" oblique (as ssr_mirror.lua), "top" straight down from 12 m over ±6.93 m.
local scene = require "scene"
scene.material "mirror" { base_color = { 0.95, 0.95, 0.95 }, metal_mask = 1, smoothness = 1 }
scene.plane "floor" { size = { 20, 20 }, material = "mirror" }
scene.material "red" { base_color = { 0.8, 0.05, 0.05 }, smoothness = 0.3, emissive = { 200, 10, 10 } }
scene.box "box" { size = { 1, 1, 1 }, position = { 0, 0.5, -2 }, material = "red" }
scene.environment "sky" { kind = "sky" }
scene.camera "main" { position = { 0, 2, 6 }, target = { 0, 0, 0 }, fov = 40, aperture = 4, shutter = 1 / 60, iso = 100 }
scene.camera "top" { position = { 0, 12, 0.0001 }, target = { 0, 0, 0 }, up = { 0, 0, -1 }, fov = 60,
                     aperture = 4, shutter = 1 / 60, iso = 100 }

local probes = scene.args.probes or "none"
if probes == "one" then
  scene.probe "front" { shape = "box", position = { 0, 0.5, -1 }, size = { 4, 3, 6 }, fade = 0.25 }
elseif probes == "priority" then
  scene.probe "left" { position = { -1.5, 1, 0 }, radius = 3, priority = 1, fade = 0.25 }
  scene.probe "right" { position = { 1.5, 1, 0 }, radius = 3, priority = 2, fade = 0.25 }
elseif probes == "size" then
  scene.probe "big" { position = { -1, 1, 0 }, radius = 4, fade = 0.25 }
  scene.probe "small" { position = { 1, 1, 0 }, radius = 2, fade = 0.25 }
elseif probes == "influence" then
  scene.probe "wide" { position = { 0, 1, 0 }, radius = 1, influence = 3, fade = 0.25 }
elseif probes == "front_first" or probes == "back_first" then
  scene.material "green" { base_color = { 0.05, 0.8, 0.05 }, smoothness = 0.3, emissive = { 10, 400, 10 } }
  scene.box "wall" { size = { 6, 4, 0.2 }, position = { 0, 2, -6 }, material = "green" }
  local front = probes == "front_first" and 2 or 1
  scene.probe "front" { position = { 0, 0.3, -0.5 }, radius = 6, priority = front, fade = 0.25 }
  scene.probe "back" { position = { 0, 0.5, -4.5 }, radius = 6, priority = 3 - front, fade = 0.25 }
else
  assert(probes == "none", "scene.args.probes: expected none, one, priority, size, influence, front_first or back_first")
end

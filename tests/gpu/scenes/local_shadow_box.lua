-- A unit box on a plane under a local light that casts shadows, seen from straight above (pixel ↔
-- world x, z; the same view as shadow_box.lua): the local shadow test scene.
-- scene.args.light: "point" (default) or "spot" (aimed at the ground beyond the box, 55° cone);
-- scene.args.box = 0 leaves the plane alone (the reference without a caster, and the acne test);
-- scene.args.x, y move the light (default −1.5, 2.5); scene.args.radius makes it a sphere light of
-- that radius (metres); scene.args.shadow = 0 turns its shadow off; scene.args.sun = 1 adds a sun
-- (1000 lux, 45° above the ground, travelling along −x) with its own cascaded shadows.
local scene = require "scene"
local kind = scene.args.light or "point"
scene.material "ground" { base_color = { 0.5, 0.5, 0.5 }, smoothness = 0.2 }
scene.plane "ground" { size = { 40, 40 }, material = "ground" }
if scene.args.box ~= 0 then
  scene.material "box" { base_color = { 0.7, 0.2, 0.1 }, smoothness = 0.3 }
  scene.box "box" { size = { 1, 1, 1 }, position = { 0, 0.5, 0 }, material = "box" }
end
local position = { scene.args.x or -1.5, scene.args.y or 2.5, 0 }
local shadow = scene.args.shadow ~= 0
if kind == "point" and scene.args.radius then
  scene.light "lamp" { type = "sphere", radius = scene.args.radius, intensity = 4000, unit = "lm", position = position, range = 30, shadow = shadow }
elseif kind == "point" then
  scene.light "lamp" { type = "point", intensity = 4000, unit = "lm", position = position, range = 30, shadow = shadow }
elseif kind == "spot" then
  scene.light "lamp" { type = "spot", intensity = 4000, unit = "lm", position = position, target = { 1.0, 0, 0 },
                       inner_angle = 50, outer_angle = 55, range = 30, shadow = shadow }
else
  error("scene.args.light: expected 'point' or 'spot'")
end
if scene.args.sun == 1 then
  scene.light "sun" { type = "sun", intensity = 1000, unit = "lux", direction = { -1, -1, 0 } }
end
scene.camera "top" { position = { 0, 12, 0.0001 }, target = { 0, 0, 0 }, up = { 0, 0, -1 }, fov = 30,
                     aperture = 4, shutter = 1 / 60, iso = 100 }

-- A unit box on a plane under the sun, seen from straight above (pixel ↔ world x, z): the shadow
-- test scene. scene.args.sun = "x45" (default: the light travels along (−1, −1, 0), 45° up from +x)
-- or "z30" (along (0, −1, √3)/2: 30° up, from −z: a long shadow towards +z). scene.args.box = 0
-- leaves the plane alone (acne test); scene.args.size scales the sun's angular radius;
-- scene.args.cast = "box" or "ground" names the one object that casts no shadow (cast_shadows = false).
local scene = require "scene"
local sun = scene.args.sun or "x45"
scene.material "ground" { base_color = { 0.5, 0.5, 0.5 }, smoothness = 0.2 }
scene.plane "ground" { size = { 40, 40 }, material = "ground", cast_shadows = scene.args.cast ~= "ground" }
if scene.args.box ~= 0 then
  scene.material "box" { base_color = { 0.7, 0.2, 0.1 }, smoothness = 0.3 }
  scene.box "box" { size = { 1, 1, 1 }, position = { 0, 0.5, 0 }, material = "box", cast_shadows = scene.args.cast ~= "box" }
end
local directions = { x45 = { -1, -1, 0 }, z30 = { 0, -0.57735, 1 } }
assert(directions[sun], "scene.args.sun: expected 'x45' or 'z30'")
scene.light "sun" { type = "sun", intensity = 50000, unit = "lux", direction = directions[sun],
                    angular_radius = 0.2664 * (scene.args.size or 1) }
-- Straight down from 12 m, "up" on screen is −z; fov 30°: the view spans ±3.2 m.
-- scene.args.dx moves the camera along x (the cascades' texel snapping test).
local dx = scene.args.dx or 0
scene.camera "top" { position = { dx, 12, 0.0001 }, target = { dx, 0, 0 }, up = { 0, 0, -1 }, fov = 30,
                     aperture = 16, shutter = 1 / 125, iso = 100 }
-- The same view through an orthographic camera of the same ground extent (±3.215 m: the
-- perspective view's at the ground), so pixel ↔ world x, z is the same linear map.
scene.camera "ortho" { position = { dx, 12, 0.0001 }, target = { dx, 0, 0 }, up = { 0, 0, -1 }, height = 6.4308,
                       aperture = 16, shutter = 1 / 125, iso = 100 }
-- A low view from the side (the nearest cascades: the ground within 2 m of the camera).
scene.camera "near" { position = { 0, 1.2, 3.4 }, target = { 0, 0.45, 0 }, fov = 45, aperture = 16, shutter = 1 / 125, iso = 100 }

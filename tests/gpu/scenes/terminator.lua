-- A sphere and a box on a floor, lit from the side, seen through an orthographic camera from above
-- the front-right (pixel ↔ a known ray, so the tests intersect the sphere and the box themselves):
-- the sun's shadow mask at the terminator. scene.args.elevation (degrees, default 30) is the sun's
-- height; it comes from +x and behind (−z), so the box's +x and top faces face it and its front
-- (+z) face does not. scene.args.back (metres, default 0; down to −6) moves the camera back along its axis:
-- the same image, further cascades.
local scene = require "scene"
local e = math.rad(scene.args.elevation or 30)
local a = math.rad(30)
local back = scene.args.back or 0
scene.material "floor" { base_color = { 0.5, 0.5, 0.5 }, smoothness = 0.2 }
scene.plane "floor" { size = { 40, 40 }, material = "floor" }
scene.material "white" { base_color = { 0.8, 0.8, 0.8 }, smoothness = 0.3 }
scene.sphere "ball" { radius = 1, position = { 1.2, 1, 0 }, segments = 96, material = "white" }
scene.box "box" { size = { 1.2, 1.2, 1.2 }, position = { -1.6, 0.6, -1.2 }, material = "white" }
-- The direction the light travels: from (cos e cos a, sin e, −cos e sin a) towards the origin.
scene.light "sun" { type = "sun", intensity = 50000, unit = "lux",
                    direction = { -math.cos(e) * math.cos(a), -math.sin(e), math.cos(e) * math.sin(a) } }
-- Looking along −(1, 0.8, 1.4)/|·| at (0, 0.8, 0) from 8 m (+ back), 5 m of height in view.
local d = { 1, 0.8, 1.4 }
local len = math.sqrt(d[1] ^ 2 + d[2] ^ 2 + d[3] ^ 2)
local r = 8 + back
scene.camera "ortho" { position = { d[1] / len * r, 0.8 + d[2] / len * r, d[3] / len * r }, target = { 0, 0.8, 0 },
                       height = 5, aperture = 16, shutter = 1 / 125, iso = 100 }

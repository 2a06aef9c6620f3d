-- Lights that reach every pixel beside lights with a range, for the standard light loop's two
-- forms (materials/standard_shading.glsl): up to four lights without a range are unrolled with
-- their types known (RG_SCENE_GLOBAL_LIGHTS), more are looped over like the tile's lights.
-- scene.args.more = 1 adds two lights without a range, of zero intensity (five in all): the same image through
-- the generic loop. A glossy dielectric and a metal on a floor, seen from above at an angle.
local scene = require "scene"
scene.material "floor" { base_color = { 0.6, 0.6, 0.6 }, smoothness = 0.5 }
scene.material "glossy" { base_color = { 0.2, 0.4, 0.8 }, smoothness = 0.8 }
scene.material "metal" { base_color = { 0.9, 0.7, 0.3 }, metal_mask = 1, smoothness = 0.6 }
scene.plane "floor" { size = { 10, 10 }, material = "floor" }
scene.sphere "ball" { radius = 0.5, position = { -0.7, 0.5, 0 }, material = "glossy" }
scene.box "box" { size = { 0.8, 0.8, 0.8 }, position = { 0.7, 0.4, 0 }, material = "metal" }
scene.camera "main" { position = { 0, 3, 4 }, target = { 0, 0.3, 0 }, fov = 45, aperture = 4, shutter = 1 / 60, iso = 100 }
scene.light "sun" { type = "sun", intensity = 20000, unit = "lux", direction = { -0.4, -0.8, -0.45 } }
if scene.args.few then
  -- scene.args.few = 1: the sun and two ranged lights whose ranges reach a quarter of the scene's
  -- diagonal (~14 m) or more: at most four lights, all unrolled and no tile loop compiled.
  -- scene.args.dark = 1: the same two at zero intensity (the sun alone lights the scene).
  local k = scene.args.dark and 0 or 1
  scene.light "near" { type = "point", intensity = 400 * k, unit = "lm", position = { 0, 0.6, 1.2 }, range = 4 }
  scene.light "globe" { type = "sphere", intensity = 600 * k, unit = "lm", radius = 0.15, position = { 1.4, 0.8, -0.6 }, range = 5 }
else
  -- Without a range: a point light and a spot light beside the sun.
  scene.light "bulb" { type = "point", intensity = 800, unit = "lm", position = { 1.5, 1.5, 1.0 } }
  scene.light "spot" { type = "spot", intensity = 1200, unit = "lm", position = { -1.5, 2.0, 1.0 }, target = { -0.5, 0, -0.2 },
                       inner_angle = 20, outer_angle = 35 }
  -- With a range: a point light and a sphere light, in the tiles' lists.
  scene.light "near" { type = "point", intensity = 400, unit = "lm", position = { 0, 0.6, 1.2 }, range = 3 }
  scene.light "globe" { type = "sphere", intensity = 600, unit = "lm", radius = 0.15, position = { 1.4, 0.8, -0.6 }, range = 4 }
end
if scene.args.more then
  scene.light "dark" { type = "point", intensity = 0, unit = "lm", position = { 0, 3, 0 } }
  scene.light "dark2" { type = "point", intensity = 0, unit = "lm", position = { 0, 3, 1 } }
end

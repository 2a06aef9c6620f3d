-- A Cornell box for baked global illumination (seed 003's SG lightmaps; rgraph bake): a 2 m room,
-- open at the front, with a red wall on the left, a green one on the right, white floor, back and
-- ceiling, two white blocks, and a 1 m² ceiling light that is baked — its direct light and its
-- bounces are in the lightmap, the real-time light loop leaves it out.
--
--   rgraph bake --scene scripts/scenes/cornell.lua
--   rgraph render --scene scripts/scenes/cornell.lua --png out/cornell.png
--
-- scene.args.light = "dynamic" keeps the light real-time instead: the lightmap then holds only its
-- bounces. scene.args.density sets the lightmap's texels per metre (default 16).
local scene = require "scene"

local W = 2.0  -- the room's width, height and depth (metres)

scene.material "white" { base_color = { 0.73, 0.73, 0.73 }, smoothness = 0.1 }
scene.material "red" { base_color = { 0.63, 0.065, 0.05 }, smoothness = 0.1 }
scene.material "green" { base_color = { 0.14, 0.45, 0.091 }, smoothness = 0.1 }

scene.plane "floor" { size = { W, W }, material = "white" }
scene.plane "ceiling" { size = { W, W }, position = { 0, W, 0 }, rotation = { 180, 0, 0 }, material = "white" }
scene.plane "back" { size = { W, W }, position = { 0, W / 2, -W / 2 }, rotation = { 90, 0, 0 }, material = "white" }
scene.plane "left" { size = { W, W }, position = { -W / 2, W / 2, 0 }, rotation = { 0, 0, -90 }, material = "red" }
scene.plane "right" { size = { W, W }, position = { W / 2, W / 2, 0 }, rotation = { 0, 0, 90 }, material = "green" }
scene.box "short" { size = { 0.6, 0.6, 0.6 }, position = { 0.35, 0.3, 0.3 }, rotation = { 0, -18, 0 }, material = "white" }
scene.box "tall" { size = { 0.6, 1.2, 0.6 }, position = { -0.35, 0.6, -0.35 }, rotation = { 0, 17, 0 }, material = "white" }

-- 2000 lm from a 0.5 m × 0.5 m panel just under the ceiling, facing down.
scene.light "ceiling_light" {
  type = "rect", intensity = 2000, unit = "lm", width = 0.5, height = 0.5,
  position = { 0, W - 0.01, 0 }, direction = { 0, -1, 0 }, up = { 0, 0, 1 },
  baked = (scene.args.light or "baked") == "baked",
}

scene.lightmap "gi" { density = tonumber(scene.args.density) or 16, lobes = 9, samples = tonumber(scene.args.samples) or 512, bounces = 3 }

scene.camera "front" {
  position = { 0, 1.0, 3.9 }, target = { 0, 1.0, 0 }, fov = 38,
  aperture = 2.8, shutter = 1 / 30, iso = 100,
}

-- The sheen material (materials/sheen.lua) in a white furnace: a row of white dielectric tiles
-- (smoothness 0.5) with a white sheen of roughness 0.25, 0.5, 0.75 and 1, and one without sheen
-- (sheen colour 0), inside a uniform environment of 1 nit and no light; seen head on by an
-- orthographic camera, so every pixel of a tile's face has N = V (tests/gpu/test_sheen.cpp).
-- scene.args.sun = 1: a black environment and a sun of 1000 lux 60° from the view instead.
local scene = require "scene"

local roughness = { 0.25, 0.5, 0.75, 1.0, 0.5 }
for i, r in ipairs(roughness) do
  local name = "cloth_" .. i
  local sheen = i < #roughness and 1 or 0
  scene.material(name) { model = "sheen", base_color = { 1, 1, 1 }, smoothness = 0.5,
                         params = { sheenColorR = sheen, sheenColorG = sheen, sheenColorB = sheen, sheenRoughnessFactor = r } }
  scene.box(name) { size = { 0.8, 0.8, 0.2 }, position = { (i - 3) * 1.0, 0, 0 }, material = name }
end

if scene.args.sun == 1 then
  scene.environment "black" { kind = "color", color = { 1, 1, 1 }, intensity = 0, unit = "nits" }
  scene.light "sun" { type = "sun", direction = { -math.sin(math.rad(60)), 0, -math.cos(math.rad(60)) }, intensity = 1000, unit = "lux" }
else
  scene.environment "white" { kind = "color", color = { 1, 1, 1 }, intensity = 1, unit = "nits" }
end

scene.camera "main" { position = { 0, 0, 10 }, target = { 0, 0, 0 }, height = 1.2, aperture = 2, shutter = 0.5, iso = 100 }

-- The transmission material (materials/transmission.lua) by its numbers (tests/gpu/test_transmission.cpp):
-- three white glass tiles turned 45° about the vertical, seen by an orthographic camera, in front
-- of an edge — an emissive wall of 10 nits left of x = 0, the black sky right of it:
--   top     thin-walled and smooth: the edge seen where it is;
--   middle  0.5 m of volume (IOR 1.5) absorbing to attenuationColor (0.5, 0.8, 1) every 0.25 m:
--           the edge moved by the refraction, its light times attenuationColor²;
--   bottom  thin-walled, roughness 0.5: the edge blurred.
-- scene.args.furnace = 1: no wall and no absorption, a uniform 1-nit environment instead — every
-- tile must vanish into it.
local scene = require "scene"

local furnace = scene.args.furnace == 1
local tiles = {
  { name = "thin", y = 0.7, smoothness = 1.0, params = {} },
  { name = "thick", y = 0.0, smoothness = 1.0,
    params = furnace and { thicknessFactor = 0.5 } or
             { thicknessFactor = 0.5, attenuationDistance = 0.25, attenuationColorR = 0.5, attenuationColorG = 0.8, attenuationColorB = 1.0 } },
  { name = "rough", y = -0.7, smoothness = 0.5, params = {} },
}
for _, t in ipairs(tiles) do
  scene.material(t.name) { model = "transmission", base_color = { 1, 1, 1 }, smoothness = t.smoothness,
                           alpha = "blend", params = t.params }
  scene.box(t.name) { size = { 0.8, 0.5, 0.02 }, position = { 0, t.y, 0 }, rotation = { 0, 45, 0 }, material = t.name }
end

if furnace then
  scene.environment "white" { kind = "color", color = { 1, 1, 1 }, intensity = 1, unit = "nits" }
else
  scene.environment "black" { kind = "color", color = { 1, 1, 1 }, intensity = 0, unit = "nits" }
  scene.material "wall" { base_color = { 0, 0, 0 }, emissive = { 10, 10, 10 } }
  scene.box "wall" { size = { 3, 3, 0.1 }, position = { -1.5, 0, -2 }, material = "wall" }
end

scene.camera "main" { position = { 0, 0, 10 }, target = { 0, 0, 0 }, height = 2.4, aperture = 2, shutter = 0.5, iso = 100 }

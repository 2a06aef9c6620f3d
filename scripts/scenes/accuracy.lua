-- The area-light accuracy suite's scene (rgraph accuracy; tests/gpu/test_accuracy.cpp): a 6 m floor
-- of one material under one area light, seen from above at 45°, so that the real-time light
-- approximations (deferred.lua) and the reference mode's Monte Carlo integration (reference.lua)
-- can be compared pixel by pixel. Nothing else in the scene: no environment, no shadowing object.
--   scene.args.light     sphere | disk | rect | tube                         (default sphere)
--   scene.args.placement facing  — 1 m above the floor, facing it
--                        grazing — 2.5 m to the side, 0.6 m up, its light skimming the floor
--                        horizon — its centre 0.2 m above the floor, crossing the floor's plane
--   scene.args.material  rough (dielectric, smoothness 0.2) | glossy (dielectric, 0.7) |
--                        metal (copper-coloured metal, 0.7)
local scene = require "scene"

local light = scene.args.light or "sphere"
local placement = scene.args.placement or "facing"
local material = scene.args.material or "rough"

local materials = {
  rough = { base_color = { 0.8, 0.8, 0.8 }, smoothness = 0.2, metal_mask = 0 },
  glossy = { base_color = { 0.8, 0.8, 0.8 }, smoothness = 0.7, metal_mask = 0 },
  metal = { base_color = { 0.95, 0.64, 0.54 }, smoothness = 0.7, metal_mask = 1 },
}
if not materials[material] then error("scene.args.material: expected rough, glossy or metal, got '" .. tostring(material) .. "'") end
scene.material "floor" (materials[material])
scene.plane "floor" { size = { 6, 6 }, material = "floor" }

-- Position and, for the oriented lights, the direction they face (disk, rect) or run (tube).
local places = {
  facing = { position = { 0, 1.0, 0 }, direction = { 0, -1, 0 }, axis = { 1, 0, 0 } },
  grazing = { position = { -2.5, 0.6, 0 }, direction = { 0.97, -0.24, 0 }, axis = { 0, 0, 1 } },
  horizon = { position = { 0, 0.2, 0 }, direction = { 0, 0, 1 }, axis = { 1, 0, 0 } },
}
local p = places[placement]
if not p then error("scene.args.placement: expected facing, grazing or horizon, got '" .. tostring(placement) .. "'") end

local lights = {
  sphere = { type = "sphere", radius = 0.3 },
  disk = { type = "disk", radius = 0.3, direction = p.direction },
  rect = { type = "rect", width = 0.8, height = 0.5, direction = p.direction,
           up = placement == "horizon" and { 0, 1, 0 } or { 0, 0, 1 } },
  tube = { type = "tube", radius = 0.05, length = 0.8, direction = p.axis },
}
local l = lights[light]
if not l then error("scene.args.light: expected sphere, disk, rect or tube, got '" .. tostring(light) .. "'") end
l.intensity, l.unit, l.position = 2000, "lm", p.position
l.visible = false  -- the light's lighting on the floor is measured, not its emissive shape
scene.light "key" (l)

scene.camera "view" {
  position = { 0, 3.0, 3.0 }, target = { 0, 0, 0 }, fov = 60, near = 0.1, far = 100,
  aperture = 2.8, shutter = 1 / 60, iso = 100,
}

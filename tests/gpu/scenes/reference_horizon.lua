-- Reference-mode test scene (scripts/pipelines/reference.lua), the horizon: a white, purely diffuse
-- floor (reflectance 0) under ONE light that crosses the floor's plane, so the floor around it sees
-- part of the light below its horizon (seed 000 §4.7.2, lst:10; seed 002 §4.7.2). The reference
-- gives that part ⟨n·l⟩ = 0 sample by sample; floor points inside a sphere or tube get nothing from
-- it there (it emits outwards). Pick the light with --scene-arg light=sphere|disk|rect|tube:
--   sphere  0.5 m radius, centre 0.2 m above the floor
--   disk    0.5 m radius, vertical, facing +z (the camera side), centre 0.2 m up
--   rect    1.2 m x 0.8 m, vertical, facing +z, centre 0.2 m up
--   tube    1.2 m long, 0.1 m radius, along x, axis 0.05 m up
-- Render it with deferred.lua and with reference.lua, then `rgraph compare` the two EXRs.
local scene = require "scene"
scene.material "floor" { base_color = { 0.8, 0.8, 0.8 }, metal_mask = 0, smoothness = 0, reflectance = 0 }
scene.plane "floor" { size = { 12, 12 }, material = "floor" }
scene.camera "top" {
  position = { 0, 3.5, 2.5 }, target = { 0, 0, 0 }, fov = 60, near = 0.1, far = 100,
  aperture = 2.8, shutter = 1 / 60, iso = 100,
}
local lights = {
  sphere = { type = "sphere", intensity = 2000, unit = "lm", radius = 0.5, position = { 0, 0.2, 0 } },
  disk = { type = "disk", intensity = 2000, unit = "lm", radius = 0.5, position = { 0, 0.2, 0 }, direction = { 0, 0, 1 } },
  rect = { type = "rect", intensity = 2000, unit = "lm", width = 1.2, height = 0.8, position = { 0, 0.2, 0 }, direction = { 0, 0, 1 } },
  tube = { type = "tube", intensity = 2000, unit = "lm", radius = 0.1, length = 1.2, position = { 0, 0.05, 0 }, direction = { 1, 0, 0 } },
}
local kind = scene.args.light or "sphere"
if not lights[kind] then error("scene.args.light: expected sphere, disk, rect or tube, got '" .. tostring(kind) .. "'") end
scene.light "key" (lights[kind])

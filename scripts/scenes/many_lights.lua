-- Many small lights over a floor with a 5x5 grid of spheres: the light-culling benchmark.
--   rgraph bench --scene scripts/scenes/many_lights.lua --scene-arg lights=256
-- scene.args.lights (default 64, 1..65536) point lights hang 0.3 m (at most half their range) over a 16 m x 16 m floor on a
-- jittered grid. Their range shrinks as the count grows so that about `overlap` lights (default
-- 4) reach each point of the floor whatever the count — the lights per pixel stay about the same
-- while the lights in the scene grow — and their flux shrinks with the area each one covers, so
-- the image keeps about the same brightness.
local scene = require "scene"

local count = scene.args.lights or 64
if type(count) ~= "number" or count ~= math.floor(count) or count < 1 or count > 65536 then
  error("scene.args.lights: expected 1..65536 lights, got " .. tostring(count))
end
local overlap = scene.args.overlap or 4
-- --scene-arg ranged=0: the same lights without a range (they reach every pixel: culling lists
-- them once for all tiles).
local ranged = (scene.args.ranged or 1) ~= 0
local size = 16
local area = size * size

scene.material "floor" { base_color = { 0.5, 0.5, 0.5 }, smoothness = 0.4 }
scene.plane "floor" { size = { size, size }, material = "floor" }
for i = 0, 4 do
  for j = 0, 4 do
    local name = string.format("ball_%d_%d", i, j)
    scene.material(name) { base_color = { 0.8, 0.8, 0.8 }, smoothness = i / 4, metal_mask = j / 4 }
    scene.sphere(name) { radius = 0.5, position = { (i - 2) * 3, 0.5, (j - 2) * 3 }, material = name, segments = 32 }
  end
end

-- N · π r² = overlap · area: each floor point lies within `overlap` ranges on average.
local range = math.sqrt(overlap * area / (math.pi * count))
-- 2000 lm per 1 m² that a light covers (π r² / overlap): the floor sees roughly the same
-- illuminance at any count.
local flux = 2000 * math.pi * range * range / overlap
-- Under half the range, so that each light's range still meets the floor when thousands shrink it.
local height = math.min(0.3, 0.5 * range)

-- A fixed linear congruential sequence: the same scene every run.
local state = 12345
local function random()
  state = (state * 1103515245 + 12345) % 2147483648
  return state / 2147483648
end
local side = math.ceil(math.sqrt(count))
local cell = size / side
for k = 0, count - 1 do
  local gx, gz = k % side, math.floor(k / side)
  scene.light(string.format("light_%d", k)) {
    type = "point", intensity = flux, unit = "lm", temperature = 2500 + 5000 * random(),
    position = { -size / 2 + (gx + random()) * cell, height, -size / 2 + (gz + random()) * cell },
    range = ranged and range or nil,
  }
end

-- --scene-arg lamp=1: one more light (the last), over the camera, whose range (100 m) reaches every
-- froxel of the view: a light the binning leaves to the pass of large lights (scripts/lighting.lua).
-- At most 65 535 lights beside it.
if (scene.args.lamp or 0) ~= 0 then
  if count > 65535 then error("scene.args.lamp: at most 65535 lights beside the lamp, got " .. count) end
  scene.light "lamp" { type = "point", intensity = 2000, unit = "lm", position = { 0, 10, 11 }, range = 100 }
end

-- --scene-arg glass=1: a blended pane over the near half of the floor, lit in the forward pass
-- from the froxels' lists (scripts/lighting.lua's lighting.clustered).
if (scene.args.glass or 0) ~= 0 then
  scene.material "glass" { base_color = { 0.9, 0.95, 1.0 }, smoothness = 0.9, alpha = "blend", opacity = 0.4, double_sided = true }
  scene.box "pane" { size = { 14, 0.02, 6 }, position = { 0, 0.12, 4 }, material = "glass" }
end

scene.camera "main" {
  position = { 0, 11, 13 }, target = { 0, 0, 0.5 }, fov = 55,
  aperture = 4, shutter = 1 / 60, iso = 800,
}

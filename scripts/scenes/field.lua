-- A field of dense meshes reaching far from the camera: the levels-of-detail benchmark.
--   rgraph bench --scene scripts/scenes/field.lua --scene-arg objects=2000
--   RG_LOD=0 rgraph bench --scene scripts/scenes/field.lua      # every draw in full, to compare
-- scene.args.objects (default 1000, 1..100000) spheres of scene.args.segments (default 45: a grid
-- that does not halve, so their levels come from meshoptimizer, graph/scene/mesh_lod.h) on a
-- jittered grid over a square floor sized so the density stays about one per 4 m², seen from
-- 1.7 m up at one corner: most are far, a few near.
local scene = require "scene"

local count = scene.args.objects or 1000
if type(count) ~= "number" or count ~= math.floor(count) or count < 1 or count > 100000 then
  error("scene.args.objects: expected 1..100000, got " .. tostring(count))
end
local segments = scene.args.segments or 45
local side = math.ceil(math.sqrt(count))
local spacing = 2
local size = side * spacing

scene.material "ground" { base_color = { 0.35, 0.33, 0.3 }, smoothness = 0.3 }
scene.plane "ground" { size = { size + 20, size + 20 }, position = { size / 2, 0, -size / 2 }, material = "ground", cast_shadows = false }
for k = 0, 3 do
  scene.material("paint" .. k) { base_color = { 0.3 + 0.15 * k, 0.5, 0.7 - 0.12 * k }, smoothness = 0.2 + 0.2 * k }
end
-- A fixed pseudo-random jitter (the same field every run).
local seed = 12345
local function random()
  seed = (seed * 1103515245 + 12345) % 2147483648
  return seed / 2147483648
end
for i = 0, count - 1 do
  local x, z = i % side, i // side
  local r = 0.3 + 0.4 * random()
  scene.sphere("s" .. i) { radius = 1, scale = r, segments = segments, material = "paint" .. (i % 4),
    position = { (x + 0.5 + 0.6 * (random() - 0.5)) * spacing, r, -(z + 0.5 + 0.6 * (random() - 0.5)) * spacing } }
end
scene.light "sun" { type = "sun", intensity = 60000, unit = "lux", direction = { 0.5, -0.6, -0.4 } }
scene.environment "sky" { kind = "sky" }
scene.camera "main" { position = { -1, 1.7, 1 }, target = { size / 2, 0.5, -size / 2 }, fov = 50, aperture = 11, shutter = 1 / 250, iso = 100 }

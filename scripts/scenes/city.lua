-- A city of many nodes: the production-scale benchmark (draw count, culling, levels of detail).
--   rgraph bench --scene scripts/scenes/city.lua --scene-arg nodes=10000
--   rgraph bench --scene scripts/scenes/city.lua --scene-arg nodes=100000 --scene-arg lamps=4096
-- scene.args.nodes (default 10000, 1..200000) nodes on a grid of 12 m lots, a street every fourth
-- lot: about seven in ten a building (a box, 6-9 m wide, mostly low, a few towers up to 80 m), the
-- rest a tree (a 24-segment sphere, 1 152 triangles: the dense meshes). scene.args.materials
-- (default 256) facade materials. scene.args.lamps (default 0, up to 65536) street lamps: ranged
-- point lights 4 m up along the streets. Seen from street level at the city's edge, looking
-- down a street, so most of the city is far and most of it hidden behind the blocks beside it.
-- scene.args.walk (default 0, up to 100): the camera walks down the street at that many metres a
-- second, turning to the right as it goes (blocks come into view and leave it every frame).
local scene = require "scene"

local function arg(name, default, lo, hi)
  local v = scene.args[name] or default
  if type(v) ~= "number" or v ~= math.floor(v) or v < lo or v > hi then
    error(string.format("scene.args.%s: expected %d..%d, got %s", name, lo, hi, tostring(v)))
  end
  return v
end
local count = arg("nodes", 10000, 1, 200000)
local materials = arg("materials", 256, 1, 4096)
local lamps = arg("lamps", 0, 0, 65536)
local walk = arg("walk", 0, 0, 100)

-- A fixed linear congruential sequence: the same city every run.
local seed = 20261129
local function random()
  seed = (seed * 1103515245 + 12345) % 2147483648
  return seed / 2147483648
end

local lot = 12
-- Lots per side, counting the streets (every fourth lot) that hold no node.
local side = math.ceil(math.sqrt(count * 4 / 3))
local size = side * lot
local function isStreet(i) return i % 4 == 3 end

scene.material "asphalt" { base_color = { 0.08, 0.08, 0.09 }, smoothness = 0.35 }
scene.plane "ground" { size = { size + 40, size + 40 }, position = { size / 2, 0, -size / 2 }, material = "asphalt", cast_shadows = false }
for k = 0, materials - 1 do
  local t = k / math.max(materials - 1, 1)
  scene.material("facade" .. k) {
    base_color = { 0.25 + 0.5 * random(), 0.25 + 0.45 * random(), 0.25 + 0.4 * random() },
    smoothness = 0.2 + 0.6 * t, metal_mask = (k % 16 == 0) and 1 or 0,
  }
end
scene.material "leaves" { base_color = { 0.12, 0.3, 0.08 }, smoothness = 0.25 }

local placed = 0
for gz = 0, side - 1 do
  if placed >= count then break end
  for gx = 0, side - 1 do
    if placed >= count then break end
    if not isStreet(gx) and not isStreet(gz) then
      local x, z = (gx + 0.5) * lot, -(gz + 0.5) * lot
      local name = "n" .. placed
      if random() < 0.7 then
        local w, d = 6 + 3 * random(), 6 + 3 * random()
        -- Mostly low blocks, a few towers: height 6 m to 80 m, skewed low.
        local h = 6 + 74 * random() ^ 4
        -- One unit box scaled (and one sphere below): every building shares a mesh, as a city's
        -- instanced props would.
        scene.box(name) { scale = { w, h, d }, position = { x, h / 2, z }, rotation = { 0, 10 * (random() - 0.5), 0 },
          material = "facade" .. math.floor(random() * materials) }
      else
        local r = 1.5 + random()
        scene.sphere(name) { radius = 1, scale = r, segments = 24, position = { x, r + 0.5, z }, material = "leaves" }
      end
      placed = placed + 1
    end
  end
end

-- Street lamps, evenly along the streets' middle lines (both ways), 4 m up, range 16 m.
local streets = {}
for i = 0, side - 1 do
  if isStreet(i) then streets[#streets + 1] = (i + 0.5) * lot end
end
if #streets == 0 then streets[1] = side * lot + lot / 2 end  -- a town too small for a street: one beside it
local lines = 2 * #streets
local perLine = math.ceil(lamps / lines)
for k = 0, lamps - 1 do
  local line, j = k % lines, k // lines
  local across = streets[line % #streets + 1]
  local along = (j + 0.5) * size / perLine
  scene.light("lamp" .. k) {
    type = "point", intensity = 3000, unit = "lm", temperature = 3000, range = 16,
    position = line < #streets and { along, 4, -across } or { across, 4, -along },
  }
end

scene.light "sun" { type = "sun", intensity = 100000, unit = "lux", direction = { 0.45, -0.7, -0.55 } }
scene.environment "sky" { kind = "sky" }
-- Down the first north-south street, a little to one side: the canyon hides most of the city.
local street = streets[1]
local start, target = { street - 2, 1.7, 2 }, { street + 0.12 * size, 6, -size }
scene.camera "main" {
  position = start, target = target, fov = 60, aperture = 16, shutter = 1 / 125, iso = 100,
  path = walk > 0 and {
    { time = 0, position = start, target = target },
    { time = 1, position = { start[1] + 1, start[2], start[3] - walk }, target = { target[1] + size, target[2], target[3] } },
  } or nil,
}

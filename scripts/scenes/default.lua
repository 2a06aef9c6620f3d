-- The default scene: a 7x7 grid of spheres over smoothness (0..1 along +x) and metal mask
-- (0..1 along +z) on a floor, a few props, a sun, a lamp, a sky, a local light probe and a
-- camera exposed for them.
--
-- Light levels are physical but not a full summer sun: 100 000 lux needs auto-exposure to look
-- right next to a lamp, so the sun here is a hazy/overcast-ish 20 000 lux. The camera follows
-- the "sunny 16" rule scaled to that: full sun (~100 000 lux, EV100 15) is f/16, 1/125 s,
-- ISO 100; 20 000 lux is ~2.3 stops less, so f/8, 1/125 s, ISO 100 (EV100 ~13).
local scene = require "scene"

local N = 7
local spacing = 1.1
local radius = 0.45

-- Gold's f0 as the base colour: at metal_mask = 0 a yellow dielectric, at 1 gold.
for i = 0, N - 1 do
  for j = 0, N - 1 do
    local name = string.format("sphere_%d_%d", i, j)
    scene.material(name) {
      base_color = { 1.0, 0.766, 0.336 },
      smoothness = i / (N - 1),
      metal_mask = j / (N - 1),
      reflectance = 0.5,
    }
    scene.sphere(name) {
      radius = radius,
      position = { (i - (N - 1) / 2) * spacing, radius, (j - (N - 1) / 2) * spacing },
      material = name,
      segments = 48,
    }
  end
end

scene.material "floor" { base_color = { 0.18, 0.18, 0.18 }, smoothness = 0.35 }
-- The ground casts no shadow: everything stands on it and every light is above it, so its depth in
-- the shadow maps could never hide anything (it still receives shadows); leaving it out spares
-- each sun cascade the fill of a plane that covers the whole map (~3 ms at 1280x720 on lavapipe).
scene.plane "floor" { size = { 24, 24 }, material = "floor", cast_shadows = false }

scene.material "crate" { base_color = { 0.55, 0.38, 0.22 }, smoothness = 0.2 }
scene.box "crate" { size = { 1.2, 1.2, 1.2 }, position = { 5.5, 0.6, -2.0 }, rotation = { 0, 30, 0 }, material = "crate" }

scene.material "steel" { base_color = { 0.56, 0.57, 0.58 }, metal_mask = 1, smoothness = 0.75 }
scene.box "pillar" { size = { 0.6, 3.0, 0.6 }, position = { -5.5, 1.5, 2.0 }, material = "steel" }

-- A small light panel: 2000 nits, about a bright LCD / a softbox face.
scene.material "panel" { base_color = { 0.05, 0.05, 0.05 }, emissive = { 2000, 1900, 1700 } }
scene.box "panel" { size = { 1.0, 0.6, 0.05 }, position = { 5.5, 1.6, 1.5 }, rotation = { 0, -60, 0 }, material = "panel" }

scene.light "sun" {
  type = "sun", intensity = 20000, unit = "lux", temperature = 5600,
  direction = { -0.45, -0.8, -0.4 },
}
-- A 100 W incandescent bulb's worth: 1600 lm, warm.
scene.light "lamp" {
  type = "point", intensity = 1600, unit = "lm", temperature = 2700,
  position = { 4.0, 2.2, 0.5 }, range = 12,
}

-- --scene-arg move=1: the camera moves (a sequence: rgraph render --frames A..B, TAA's moving
-- case) — over two seconds it swings right and down towards the grid, through three keys.
scene.camera "main" {
  position = { 0.0, 5.0, 10.5 }, target = { 0.0, 0.3, 0.0 }, fov = 40,
  aperture = 8, shutter = 1 / 125, iso = 100,
  path = scene.args.move and {
    { time = 0, position = { 0.0, 5.0, 10.5 }, target = { 0.0, 0.3, 0.0 } },
    { time = 1, position = { 3.0, 4.0, 9.0 }, target = { 0.5, 0.3, 0.0 } },
    { time = 2, position = { 5.0, 3.0, 7.0 }, target = { 1.0, 0.3, 0.0 } },
  } or nil,
}

scene.environment "sky" { kind = "sky", intensity = 1, unit = "nits" }

-- A local light probe over the sphere grid and its props (seed 002 §4.9.1.2): captured once from
-- 1.2 m above the middle of the grid, its box the proxy the reflections are parallax-corrected
-- against, fading over the outer metre.
scene.probe "grid" { shape = "box", position = { 0.0, 1.2, 0.0 }, size = { 14, 6, 12 }, fade = 1 }

-- Baked GI (seed 003's SG lightmaps), on request: --scene-arg lightmap=1 (rgraph bake, then render).
-- The sun and the lamp stay dynamic; the lightmap holds the sky and their bounces.
if scene.args.lightmap then
  scene.lightmap "gi" { density = tonumber(scene.args.lightmap_density) or 4, lobes = tonumber(scene.args.lobes) or 9, samples = 128, bounces = 2 }
end

-- Every material of the default loop and of the example packages in one scene: a row of spheres
-- (standard, clear coat, two-colour, toon, skin), a blended toon pane, foliage-material leaves on
-- a stem, a standard floor, and a decal across the row (it paints each material what that
-- material lets decals paint: the toon's tint, the skin's colour, the standard's metal too).
local scene = require "scene"
scene.material "floor" { base_color = { 0.5, 0.5, 0.5 }, smoothness = 0.3 }
scene.plane "floor" { size = { 10, 10 }, material = "floor" }
scene.material "gold" { base_color = { 1.0, 0.77, 0.34 }, metal_mask = 1, smoothness = 0.8 }
scene.material "lacquer" { model = "clear_coat", base_color = { 0.6, 0.05, 0.05 }, smoothness = 0.4, params = { coatSmoothness = 0.95 } }
scene.material "oxide" { model = "two_colour", diffuse_color = { 0.25, 0.12, 0.06 }, f0 = { 0.55, 0.45, 0.2 }, smoothness = 0.6 }
scene.material "cel" { model = "toon", base_color = { 0.1, 0.6, 0.6 }, params = { toonBands = 4 } }
scene.material "skin" { model = "skin", base_color = { 0.8, 0.55, 0.45 }, smoothness = 0.45 }
scene.material "leaf" { model = "foliage", base_color = { 0.2, 0.45, 0.1 }, smoothness = 0.3 }
scene.material "ghost" { model = "toon", base_color = { 0.8, 0.8, 0.9 }, alpha = "blend", opacity = 0.5, params = { toonBands = 2 } }
local row = { "gold", "lacquer", "oxide", "cel", "skin" }
for i, m in ipairs(row) do
    scene.sphere(m .. "_sphere") { radius = 0.4, position = { (i - 3) * 0.95, 0.4, 0 }, material = m }
end
scene.box "leaves" { size = { 0.6, 0.6, 0.05 }, position = { 2.9, 0.6, -0.3 }, rotation = { 0, -30, 0 }, material = "leaf" }
scene.box "pane" { size = { 0.7, 0.7, 0.02 }, position = { -2.6, 0.45, 0.6 }, material = "ghost" }
scene.decal "stripe" { position = { 0, 0.4, 0.35 }, size = { 5.0, 0.1, 0.4 }, base_color = { 0.1, 0.15, 0.6 },
                       metal_mask = 0, opacity = 0.9 }
scene.light "sun" { type = "sun", intensity = 50000, unit = "lux", direction = { -0.5, -0.6, -0.5 } }
scene.environment "sky" { kind = "sky" }
scene.camera "main" { position = { 0, 1.4, 4.6 }, target = { 0, 0.45, 0 }, fov = 50, aperture = 16, shutter = 1 / 125, iso = 100 }

-- The toon package's example scene: toon spheres (three and five bands), a blended toon pane
-- (the forward pass lights it with the toon path), a standard floor, and a decal over a toon
-- sphere and the floor (it paints the toon's tint; metal only on the floor).
local scene = require "scene"
scene.material "floor" { base_color = { 0.5, 0.5, 0.5 }, smoothness = 0.3 }
scene.plane "floor" { size = { 8, 8 }, material = "floor" }
scene.material "orange" { model = "toon", base_color = { 0.9, 0.4, 0.1 }, params = { toonBands = 3 } }
scene.sphere "three" { radius = 0.5, position = { -0.6, 0.5, 0 }, material = "orange" }
scene.material "teal" { model = "toon", base_color = { 0.1, 0.6, 0.6 }, params = { toonBands = 5, toonWrap = 0.0, toonRim = 0.0 } }
scene.sphere "five" { radius = 0.5, position = { 0.6, 0.5, 0 }, material = "teal" }
scene.material "ghost" { model = "toon", base_color = { 0.8, 0.8, 0.9 }, alpha = "blend", opacity = 0.5, params = { toonBands = 2 } }
scene.box "pane" { size = { 0.7, 0.7, 0.02 }, position = { 1.6, 0.45, 0.6 }, material = "ghost" }
scene.decal "paint" { position = { -0.6, 0.5, 0.45 }, size = { 0.5, 0.5, 0.5 }, base_color = { 0.1, 0.2, 0.9 },
                      smoothness = 0.9, metal_mask = 1, opacity = 1 }
scene.light "sun" { type = "sun", intensity = 50000, unit = "lux", direction = { -0.4, -0.8, -0.45 } }
scene.environment "sky" { kind = "sky" }
scene.camera "main" { position = { 0, 1.3, 3.4 }, target = { 0.2, 0.45, 0 }, fov = 45, aperture = 16, shutter = 1 / 125, iso = 100 }

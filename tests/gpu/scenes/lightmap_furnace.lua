-- A furnace for the baked lightmap (tests/gpu/test_lightmap_render.cpp): a 4 m plane in a uniform
-- 1-nit white environment, nothing else. Every direction above the plane brings 1 nit, so the
-- lightmap's radiance is 1 over the hemisphere, its irradiance π, and its pre-filtered specular
-- radiance 1 whatever the roughness and the view.
local scene = require "scene"
scene.material "plane" { base_color = { 0.8, 0.8, 0.8 }, smoothness = tonumber(scene.args.smoothness) or 0.5,
                         ao = tonumber(scene.args.ao) or 1 }
scene.plane "plane" { size = { 4, 4 }, material = "plane" }
scene.environment "white" { kind = "color", color = { 1, 1, 1 }, intensity = 1 }
scene.lightmap "gi" { density = 8, samples = 256, bounces = 1 }
scene.camera "oblique" { position = { 0, 1.5, 3 }, target = { 0, 0, 0 }, fov = 50 }

-- Reference-mode test scene (scripts/pipelines/reference.lua): reference_stage.lua's floor and
-- four spheres under ONE tube light along x (seed 002 §4.7.2.6: rectangle + sphere). Render it with deferred.lua and with
-- reference.lua, then `rgraph compare` the two EXRs.
local scene = require "scene"
require "reference_stage"  -- the floor, four spheres and the camera
scene.light "key" { type = "tube", intensity = 3000, unit = "lm", radius = 0.05, length = 1.6, position = { 0, 1.5, 1.0 }, direction = { 1, 0, 0 } }

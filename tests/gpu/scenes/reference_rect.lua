-- Reference-mode test scene (scripts/pipelines/reference.lua): reference_stage.lua's floor and
-- four spheres under ONE one-sided rectangle light (structured sampling, seed 002 §4.7.2.5). Render it with deferred.lua
-- and with reference.lua, then `rgraph compare` the two EXRs.
local scene = require "scene"
require "reference_stage"  -- the floor, four spheres and the camera
scene.light "key" { type = "rect", intensity = 3000, unit = "lm", width = 1.6, height = 0.5, up = { 0, 0, 1 }, position = { 0, 1.8, 1.0 }, direction = { 0, -1, -0.2 } }

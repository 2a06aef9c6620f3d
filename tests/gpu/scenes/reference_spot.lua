-- Reference-mode test scene (scripts/pipelines/reference.lua): reference_stage.lua's floor and
-- four spheres under ONE spot light (delta, exact in both). Render it with deferred.lua and with reference.lua, then
-- `rgraph compare` the two EXRs.
local scene = require "scene"
require "reference_stage"  -- the floor, four spheres and the camera
scene.light "key" { type = "spot", intensity = 3000, unit = "lm", position = { 0, 2.5, 1.5 }, target = { 0, 0, 0 }, inner_angle = 20, outer_angle = 35 }

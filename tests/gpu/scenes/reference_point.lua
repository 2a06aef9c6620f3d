-- Reference-mode test scene (scripts/pipelines/reference.lua): reference_stage.lua's floor and
-- four spheres under ONE point light (delta: the reference evaluates it exactly, so the two must match). Render it with
-- deferred.lua and with reference.lua, then `rgraph compare` the two EXRs.
local scene = require "scene"
require "reference_stage"  -- the floor, four spheres and the camera
scene.light "key" { type = "point", intensity = 2000, unit = "lm", position = { 0, 1.6, 1.0 } }

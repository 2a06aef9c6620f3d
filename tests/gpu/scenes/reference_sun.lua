-- Reference-mode test scene (scripts/pipelines/reference.lua): reference_stage.lua's floor and
-- four spheres under ONE 100 000 lux sun of the default angular radius 0.2664° (lst:6). Render it with deferred.lua and
-- with reference.lua, then `rgraph compare` the two EXRs.
local scene = require "scene"
require "reference_stage"  -- the floor, four spheres and the camera
scene.light "key" { type = "sun", intensity = 100000, unit = "lux", direction = { -0.4, -0.8, -0.45 } }

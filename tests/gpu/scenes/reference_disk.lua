-- Reference-mode test scene (scripts/pipelines/reference.lua): reference_stage.lua's floor and
-- four spheres under ONE one-sided disk light tilted towards the spheres (lst:10 × ⟨n_light·−l⟩ diffuse). Render it with
-- deferred.lua and with reference.lua, then `rgraph compare` the two EXRs.
local scene = require "scene"
require "reference_stage"  -- the floor, four spheres and the camera
scene.light "key" { type = "disk", intensity = 3000, unit = "lm", radius = 0.4, position = { 0, 1.8, 1.2 }, direction = { 0, -1, -0.4 } }

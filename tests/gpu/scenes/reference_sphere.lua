-- Reference-mode test scene (scripts/pipelines/reference.lua): reference_stage.lua's floor and
-- four spheres under ONE sphere light (lst:10 diffuse, representative-point specular). Render it with deferred.lua and
-- with reference.lua, then `rgraph compare` the two EXRs.
local scene = require "scene"
require "reference_stage"  -- the floor, four spheres and the camera
scene.light "key" { type = "sphere", intensity = 3000, unit = "lm", radius = 0.3, position = { 0, 1.6, 1.0 } }

-- Reference-mode test scene (scripts/pipelines/reference.lua): reference_stage.lua's floor and
-- four spheres under ONE 0.5 mm sphere light of the same 2000 lm as reference_point.lua: the reference of this scene must
-- converge to the deferred render of reference_point.lua (checks area sampling + MIS against a
-- delta light). Render it with deferred.lua and with reference.lua, then `rgraph compare` the two
-- EXRs.
local scene = require "scene"
require "reference_stage"  -- the floor, four spheres and the camera
scene.light "key" { type = "sphere", intensity = 2000, unit = "lm", radius = 0.0005, position = { 0, 1.6, 1.0 } }

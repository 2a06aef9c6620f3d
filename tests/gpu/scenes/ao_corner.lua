-- Ambient occlusion test scene: a floor, two 2 m walls meeting at a corner at the origin along
-- +x and +z, seen from straight above (pixel ↔ world x, z). scene.args.open = 1 leaves the
-- floor alone (an open plane: AO 1 everywhere).
local scene = require "scene"
scene.material "grey" { base_color = { 0.5, 0.5, 0.5 }, smoothness = 0.2 }
scene.plane "floor" { size = { 40, 40 }, material = "grey" }
if scene.args.open ~= 1 then
  scene.box "wall_x" { size = { 0.1, 2, 8 }, position = { -0.05, 1, 4 }, material = "grey" }
  scene.box "wall_z" { size = { 8, 2, 0.1 }, position = { 4, 1, -0.05 }, material = "grey" }
end
scene.environment "sky" { kind = "sky" }
-- Straight down at (2.5, 0, 2.5) from 10 m; "up" on screen is −z; fov 40°: the view spans ±3.64 m.
scene.camera "top" { position = { 2.5, 10, 2.5001 }, target = { 2.5, 0, 2.5 }, up = { 0, 0, -1 }, fov = 40 }
-- A low view over the open floor (the grazing case).
scene.camera "low" { position = { 0, 1.2, 8 }, target = { 0, 0, 0 }, fov = 50 }

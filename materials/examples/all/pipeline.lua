-- The default pipeline with every example package of this folder's parent at once: the built-in
-- materials (standard, clear coat, foliage, two-colour), toon and skin, each on its own lighting
-- path and with its own identity. Run from the project:
--   rgraph render --pipeline materials/examples/all/pipeline.lua --scene materials/examples/all/scene.lua
--   rgraph graph --pipeline materials/examples/all/pipeline.lua --format materials
require "pipelines.deferred"  -- rgraph's default pipeline, unchanged
require "examples.toon.toon"  -- materials/examples/toon/toon.lua (materials/ is a module folder)
require "examples.skin.skin"  -- materials/examples/skin/skin.lua

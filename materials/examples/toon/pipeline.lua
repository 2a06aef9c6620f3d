-- The default pipeline with the toon package: copy this folder anywhere and run
--   rgraph render --pipeline FOLDER/pipeline.lua --scene FOLDER/scene.lua
require "pipelines.deferred"  -- rgraph's default pipeline, unchanged
require "toon"                -- this folder's toon.lua: its material, layout, path and lighting pass

-- The default pipeline with the skin package: copy this folder anywhere and run
--   rgraph render --pipeline FOLDER/pipeline.lua --scene FOLDER/scene.lua
require "pipelines.deferred"  -- rgraph's default pipeline, unchanged
require "skin"                -- this folder's skin.lua: its material, layout, path and lighting pass

local rg = require "rg"
rg.buffer "lists" { size = 16, scene_count = "shadow_casters" }

local rg = require "rg"
rg.resource "maps" { format = "d32f", size = { 64, 64 }, layers = 4, scene_layers = "shadow views" }
rg.output "maps"

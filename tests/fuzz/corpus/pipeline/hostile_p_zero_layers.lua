local rg = require "rg"
rg.resource "r" { format = "rgba8", layers = 0 }
rg.output "r"

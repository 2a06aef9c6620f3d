local rg = require "rg"
rg.resource "r" { format = "rgba8" }
rg.resource "r" { format = "rgba16f" }
rg.output "r"

local rg = require "rg"
rg.resource "r" { format = "rgb9" }
rg.output "r"

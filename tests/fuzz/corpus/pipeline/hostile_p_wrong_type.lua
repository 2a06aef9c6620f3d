local rg = require "rg"
rg.resource "r" { format = 5 }
rg.output "r"

local rg = require "rg"
rg.resource "output" { format = 16 }
rg.output "output"

local rg = require "rg"
rg.buffer "lists" { size = 16, tile = 8 }

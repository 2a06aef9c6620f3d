local rg = require "rg"
rg.param "x" { type = "number", default = 5, min = 0, max = 1 }

local rg = require "rg"
rg.param "exposure" { type = "number", default = 20, min = -6, max = 16 }

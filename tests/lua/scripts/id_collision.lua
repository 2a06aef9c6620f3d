local rg = require "rg"
require "disney"
rg.material "clearcoat" { id = 1, layout = "disney", path = "standard" }
rg.material "foliage" { id = 1, layout = "disney", path = "standard" }

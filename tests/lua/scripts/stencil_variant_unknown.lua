local rg = require "rg"
require "disney"
rg.stencil "wet" { variant_of = "lit_standrd" }

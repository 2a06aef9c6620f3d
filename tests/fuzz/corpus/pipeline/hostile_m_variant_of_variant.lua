require "pipelines.deferred"
local rg = require "rg"
rg.stencil "wet_foliage" { variant_of = "foliage" }

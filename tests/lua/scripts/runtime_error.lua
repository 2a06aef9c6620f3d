local rg = require "rg"
local settings = nil
rg.param "exposure" { type = "number", default = settings.exposure }

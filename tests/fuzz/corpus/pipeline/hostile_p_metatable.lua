local rg = require "rg"
setmetatable(_G, { __index = function(_, k) error("trap " .. k) end })
rg.resource "r" { format = "rgba8" }
rg.output(undefined_global)

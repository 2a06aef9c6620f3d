local rg = require "rg"
local n = 0
while true do n = n + 1 end

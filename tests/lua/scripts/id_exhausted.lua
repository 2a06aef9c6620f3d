local rg = require "rg"
require "disney"
-- Sixteen more materials on the standard path, each with other decals: lit_standard has 16 values.
local params = { "normal", "baseColor", "smoothness", "metalMask", "reflectance" }
for k = 1, 16 do
    local decals = {}
    for b = 0, 4 do
        if k & (1 << b) ~= 0 then decals[#decals + 1] = params[b + 1] end
    end
    rg.material("m" .. k) { layout = "disney", path = "standard", decals = decals }
end

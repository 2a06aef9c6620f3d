local rg = require "rg"
-- rgraph allocates stencil classes from 4 bits: 15 classes fit, the 16th does not.
for i = 1, 16 do
    rg.stencil("class" .. i) {}
end

-- Stencil- and depth-tested fullscreen passes against a cleared depth/stencil buffer
-- (depth 0.5, stencil 3): only the passes whose test passes leave their colour.
local rg = require "rg"
rg.resource "ds" { format = "d32f_s8" }
for _, name in ipairs { "hit", "miss", "near", "far" } do rg.resource(name) { format = "rgba16f", export = true } end
rg.pass "clear_ds" { kind = "clear", writes = { "ds" }, depth = 0.5, stencil = 3 }
local function tested(name, fields)
    local pass = { kind = "fullscreen", shader = "test/tint.frag", reads = { { "ds", as = "depth" } }, writes = { name },
                   uniforms = { tint = { 1, 0.5, 0.25, 1 } } }
    for k, v in pairs(fields) do pass[k] = v end
    rg.pass(name) (pass)
end
tested("hit", { stencil = { ref = 3, compare = "equal" } })
tested("miss", { stencil = { ref = 2, compare = "equal" } })
tested("near", { depth = { compare = "less", value = 0.25 } })
tested("far", { depth = { compare = "less", value = 0.75 } })
rg.output "hit"

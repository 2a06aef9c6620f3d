-- rg.frame fills the Lua memory and keeps it: every later frame must fail cleanly too, with the
-- memory message, and never abort the process.
local rg = require "rg"
rg.resource "out" { format = "rgba8" }
rg.pass "fill" { kind = "clear", writes = { "out" } }
rg.output "out"
-- A linked list of small tables: memory runs out on a small allocation.
hoard = nil
function rg.frame(ctx)
    for i = 1, 100000000 do hoard = { next = hoard } end
end

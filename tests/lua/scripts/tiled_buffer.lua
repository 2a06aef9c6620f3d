-- A screen-tiled buffer: 16 bytes plus 64 per 8x8-pixel tile of the output.
local rg = require "rg"
rg.buffer "lists" { size = 16, tile = 8, tile_bytes = 64 }
rg.resource "out" { format = "rgba8" }
rg.pass "fill" { kind = "clear", writes = { "lists" } }
rg.pass "keep" { kind = "readback", reads = { "lists" }, side_effect = true }
rg.pass "show" { kind = "clear", writes = { "out" } }
rg.output "out"

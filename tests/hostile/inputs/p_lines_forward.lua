-- A scene pass that would draw the points and lines and be the forward pass at once.
local rg = require "rg"
require "disney"  -- the standard material the default scene uses
rg.resource "depth" { format = "d32f" }
rg.resource "hdr" { format = "rgba16f" }
rg.pass "clear_depth" { kind = "clear", writes = { "depth" }, value = 1 }
rg.pass "clear_hdr" { kind = "clear", writes = { "hdr" } }
rg.pass "strokes" { kind = "scene", lines = true, forward = true,
    reads = { { "depth", as = "depth" } }, writes = { { "hdr", load = true } } }
rg.output "hdr"

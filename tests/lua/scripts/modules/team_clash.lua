-- Writes the pipeline's output from scratch, with no order against the pipeline's own writer.
local rg = require "rg"
local m = rg.module "team_clash"
m.pass "overwrite" { kind = "fullscreen", shader = "test/tint.frag", writes = { "output" }, uniforms = { tint = { 1, 1, 1, 1 } } }
return m

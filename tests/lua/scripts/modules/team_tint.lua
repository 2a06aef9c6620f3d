-- A module from another team: its own resource, a pass inserted after "transform".
local rg = require "rg"
local m = rg.module "team_tint"
m.resource "overlay" { format = "rgba16f" }
m.pass "make_overlay" { kind = "clear", writes = { "overlay" }, value = { 0, 0.5, 0, 0 }, insert = { after = "transform" } }
m.pass "apply" {
    kind = "fullscreen", shader = "test/tint.frag", blend = "additive", reads = { "overlay" },
    writes = { { "output", load = true } }, uniforms = { tint = { 0, 0, 0.125, 0 } },
    insert = { after = "transform" },
}
return m

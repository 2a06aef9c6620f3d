local rg = require "rg"
rg.resource "a" { format = "rgba16f" }
rg.resource "output" { format = "rgba16f", export = true }
rg.pass "first" { kind = "fullscreen", shader = "test/tint.frag", writes = { "a" }, after = { "second" } }
rg.pass "second" { kind = "fullscreen", shader = "test/transform.frag", reads = { "a" }, writes = { "output" }, bind = { pattern = "a" } }
rg.output "output"

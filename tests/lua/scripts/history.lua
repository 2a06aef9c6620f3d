-- rg.resource's `history`: `count` is its last frame (`count_history`) plus `step`, written by
-- `count` or, switched, by `count_twice`; `hundred` is a compiled-in switch of `count`.
local rg = require "rg"
rg.param "step" { type = "number", default = 1 }
rg.param "hundred" { type = "boolean", default = false }
rg.resource "count" { format = "rgba32f", history = "count_history" }
rg.pass "count" { kind = "fullscreen", shader = "test/count.frag", reads = { "count_history" }, writes = { "count" },
    switches = { hundred = "RG_COUNT_HUNDRED" } }
rg.pass "count_twice" { kind = "fullscreen", shader = "test/count.frag", reads = { "count_history" }, writes = { "count" },
    enabled = false, after = { "count" }, uniforms = { step = 2 } }
rg.output "count"

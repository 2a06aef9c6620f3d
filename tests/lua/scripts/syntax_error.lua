local rg = require "rg"
rg.pass "broken" { kind = "fullscreen",

local rg = require "rg"
rg.pass "a" {

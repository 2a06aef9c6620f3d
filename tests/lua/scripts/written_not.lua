-- A scene pass's lightmap_specular names a resource the pass does not write.
local rg = require "rg"
require "disney"
rg.resource "GB0" { format = "rgb10a2" }
rg.resource "GB1" { format = "rgba8_srgb" }
rg.resource "GB2" { format = "rgba8" }
rg.resource "GB3" { format = "rgba16f" }
rg.resource "depth" { format = "d32f_s8" }
rg.resource "spec" { format = "rgba16f" }
rg.pass "gbuffer" { kind = "scene", writes = { "GB0", "GB1", "GB2", "GB3", "depth" }, lightmap_specular = "spec" }
rg.output "GB0"

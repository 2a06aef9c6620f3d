local rg = require "rg"
rg.resource "GB0" { format = "rgb10a2" }
rg.resource "GB1" { format = "rgba8_srgb" }
rg.resource "GB2" { format = "rgba8" }
rg.resource "hdr" { format = "rgba16f" }
rg.pass "lighting" {
    kind = "fullscreen", shader = "test/tint.frag",
    reads = { "GB0", "GB1", "GB9" }, writes = { "hdr" },
}
rg.output "hdr"

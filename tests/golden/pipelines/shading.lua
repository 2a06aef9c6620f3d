-- A small deferred renderer over an analytic scene (a sphere on a checkered ground under a sun
-- and a sky) for the golden tests: its goldens hold real shading — world normals, sRGB albedo,
-- integer material ids, HDR radiance with highlights above 1 and an 8-bit display image — and
-- run the transcendental maths (pow, exp2, sqrt, normalize) where lavapipe's output can change
-- with the host CPU. `dither` and `jitter` default to on: the golden runner's determinism
-- profile switches them off.
local rg = require "rg"

rg.param "sun_elevation" { type = "number", default = 35, min = 0, max = 90, doc = "degrees above the horizon" }
rg.param "sun_intensity" { type = "number", default = 3, min = 0, max = 100, doc = "sun radiance scale" }
rg.param "exposure" { type = "number", default = 0, min = -10, max = 10, doc = "EV applied before the tone map" }
rg.param "dither" { type = "boolean", default = true, doc = "ordered dither before the 8-bit display target" }
rg.param "jitter" { type = "number", default = 0.5, min = 0, max = 1, doc = "sub-pixel camera jitter (TAA), in pixels" }

rg.resource "normal" { format = "rgba16f" }    -- xyz: world normal; w: hit distance (0: sky)
rg.resource "albedo" { format = "rgba8_srgb" }
rg.resource "material" { format = "r8ui" }     -- 0 sky, 1 sphere, 2 ground
rg.resource "hdr" { format = "rgba16f" }
rg.resource "ldr" { format = "rgba8" }         -- sRGB-encoded display values

rg.pass "surface" { kind = "fullscreen", shader = "shading_surface.frag", writes = { "normal", "albedo", "material" } }
rg.pass "lighting" {
    kind = "fullscreen", shader = "shading_lighting.frag", filter = "nearest",
    reads = { "normal", "albedo", "material" }, writes = { "hdr" },
}
rg.pass "display" { kind = "fullscreen", shader = "shading_display.frag", reads = { "hdr" }, writes = { "ldr" } }

rg.output "ldr"

-- Shadows (seed 002 §4.10.4; DESIGN §10): the sun's cascaded shadow map.
--
--   local shadows = require "shadows"   -- declares the map, its cascades and the passes
--   rg.pass "lighting_x" (shadows.lit { kind = "fullscreen", shader = ..., reads = { ... }, ... })
--
-- Each frame `sun_cascades` (compute, one invocation: shaders/shadows/sun_cascades.comp) places
-- shadows.cascades cascades over the view up to `shadow_distance` (practical split scheme,
-- stable by texel snapping), and `shadow_sun` (the `scene` kind with shadow = true) draws every
-- opaque primitive's depth into `sun_shadow`, one layer per cascade. Both
-- are culled by the graph when nothing reads the map, and skipped (rg.frame: shadows.frame) when
-- the scene has no sun or `sun_shadows` is off. `shadows.lit` makes a lighting pass read them: lib/shadows.glsl's PCSS
-- (blocker search, penumbra from the sun's angular size) multiplies the sun's light.
local rg = require "rg"
local lighting = require "lighting"

local shadows = {}

shadows.size = 2048    -- texels per side of each cascade
shadows.cascades = 3   -- 1..4 (3: each costs a draw of every caster)

rg.param "sun_shadows" { type = "boolean", default = true, doc = "the sun casts shadows (false: the map is only cleared)" }
rg.param "shadow_distance" { type = "number", default = 40, min = 1, max = 10000, doc = "metres of view the sun's cascades cover" }
rg.param "shadow_split_lambda" { type = "number", default = 0.8, min = 0, max = 1, doc = "cascade splits: 0 uniform .. 1 logarithmic (practical split scheme)" }
rg.param "shadow_depth_bias" { type = "number", default = 0.02, min = 0, max = 1, doc = "receiver depth bias, metres along the light" }
rg.param "shadow_normal_offset" { type = "number", default = 1.5, min = 0, max = 16, doc = "lookup offset along the normal, in texels of the cascade" }
rg.param "shadow_softness" { type = "number", default = 1, min = 0, max = 16, doc = "penumbra width × the sun's physical one (0: hard)" }

rg.buffer "sun_cascades" { size = 4 * 64 + 5 * 16, doc = "the sun's cascades this frame (lib/shadows.glsl's RgCascades)" }
rg.resource "sun_shadow" { format = "d32f", size = { shadows.size, shadows.size }, layers = shadows.cascades,
    doc = "the sun's shadow map, one layer per cascade" }

rg.pass "sun_cascades" {
    kind = "compute", shader = "shadows/sun_cascades.comp", writes = { { "sun_cascades", as = "storage" } }, groups = { 1, 1, 1 },
    defines = { RG_CASCADES = shadows.cascades, RG_SHADOW_SIZE = shadows.size },
}
-- Without a sun the map is only cleared (to "nothing in the way"): shadows.frame switches
-- between the two writers.
rg.pass "shadow_clear" { kind = "clear", writes = { "sun_shadow" }, depth = 1 }
rg.pass "shadow_sun" {
    kind = "scene", shadow = true, reads = { { "sun_cascades", as = "storage" } }, writes = { "sun_shadow" },
    depth_bias = { 1.0, 1.5 }, after = { "shadow_clear" },
}

-- A lighting pass's declaration, shadowed: reads the map and the cascades, defines RG_SHADOWS.
function shadows.lit(pass)
    return lighting.extend(pass, { "sun_shadow", { "sun_cascades", as = "storage" } }, "RG_SHADOWS")
end

-- Per frame: no sun in the scene (or sun_shadows off), no shadow draws — the map is cleared
-- instead, and everything reads as lit.
function shadows.frame(ctx)
    local draw = ctx.params.sun_shadows and (not ctx.scene or ctx.scene.suns > 0)
    ctx.pass("shadow_sun").enabled = draw
    ctx.pass("shadow_clear").enabled = not draw
end

return shadows

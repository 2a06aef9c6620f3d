-- A reconfiguration sequence over five frames. The pipeline's own rg.frame disables the additive
-- tint on frame 1 and enables it on frame 2; then this test's frame callback halves `scale` on
-- frame 3 (a parameter: uniforms only) and disables the tint again on frame 4 (a rebuild). The
-- golden is the fifth frame: no tint, half scale.
return {
    doc = "tests/lua/scripts/reconfigure.lua driven by its own rg.frame and the test's frame callback",
    pipeline = "tests/lua/scripts/reconfigure.lua",
    size = { 64, 32 },
    frames = 5,
    frame = function(ctx)
        if ctx.frame == 3 then ctx.params.scale = 0.5 end
        if ctx.frame == 4 then ctx.pass("tint").enabled = false end
    end,
    captures = {
        output = { metric = "max_abs", tolerance = 0 },
    },
}

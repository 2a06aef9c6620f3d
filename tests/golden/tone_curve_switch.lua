-- A switch changed by the test's frame callback: the post chain's tone curve is compiled into the
-- tonemap pass (scripts/post.lua: switches), so setting it on frame 1 rebuilds that pass rather
-- than updating a uniform. The golden is the second frame, through the linear curve: the same
-- image `rgraph render --pipeline tests/lua/scripts/post_uniform.lua --set tonemap=linear` gives
-- (checked when it was blessed), where the default ACES curve compresses the highlight.
return {
    doc = "tests/lua/scripts/post_uniform.lua with its tone curve switched from aces to linear on frame 1",
    pipeline = "tests/lua/scripts/post_uniform.lua",
    size = { 32, 16 },
    frames = 2,
    frame = function(ctx)
        ctx.params.exposure_mode = "manual"
        if ctx.frame == 1 then ctx.params.tonemap = "linear" end
    end,
    captures = {
        display = { metric = "max_abs", tolerance = 0 },
    },
}

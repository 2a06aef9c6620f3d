-- The default pipeline with the foliage fix-up switched off from the first frame on.
require "pipelines.deferred"
function rg.frame(ctx)
    ctx.pass("foliage_fixup").enabled = false
end

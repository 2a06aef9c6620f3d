-- The smallest pipeline (compute pattern -> fullscreen transform) with a parameter set by the
-- test: output = (g, r, 1 - b, 1) * scale with scale = 0.5.
return {
    doc = "scripts/pipelines/test.lua at scale 0.5",
    pipeline = "scripts/pipelines/test.lua",
    size = { 64, 48 },
    params = { scale = 0.5 },
    captures = {
        pattern = { metric = "max_abs", tolerance = 0 },
        output = { { metric = "max_abs", tolerance = 0 }, { metric = "rmse", tolerance = 0 } },
    },
}

-- Every pass of the default pipeline (scripts/pipelines/deferred.lua), three frames so that
-- auto-exposure adapts: the test card (card), its HDR presentation (present -> hdr), the bloom
-- chain down and up, the exposure state the histogram passes meter (a buffer of 4 floats), the
-- tone-mapped image (tonemap -> display_ldr) and the anti-aliased display image (fxaa). The
-- profile switches the post chain's dither off and pins its frame_time to 1/60 s.
return {
    doc = "the default pipeline: test card, HDR, bloom, auto-exposure, tone map, FXAA",
    pipeline = "scripts/pipelines/deferred.lua",
    size = { 128, 96 },
    frames = 3,
    captures = {
        card = { metric = "max_abs", tolerance = 0 },
        hdr = { { metric = "rel_mean", channels = "rgb", tolerance = 1e-4 }, { metric = "rel_max", channels = "rgb", tolerance = 2e-3 } },
        bloom_down1 = { metric = "rel_max", channels = "rgb", tolerance = 2e-3 },
        bloom_down2 = { metric = "rel_max", channels = "rgb", tolerance = 2e-3 },
        bloom_down3 = { metric = "rel_max", channels = "rgb", tolerance = 2e-3 },
        bloom_down4 = { metric = "rel_max", channels = "rgb", tolerance = 2e-3 },
        bloom_down5 = { metric = "rel_max", channels = "rgb", tolerance = 2e-3 },
        bloom_up4 = { metric = "rel_max", channels = "rgb", tolerance = 2e-3 },
        bloom_up3 = { metric = "rel_max", channels = "rgb", tolerance = 2e-3 },
        bloom_up2 = { metric = "rel_max", channels = "rgb", tolerance = 2e-3 },
        bloom_up1 = { metric = "rel_max", channels = "rgb", tolerance = 2e-3 },
        exposure = { metric = "rel_max", tolerance = 1e-5 },
        display_ldr = {
            { metric = "flip", channels = "rgb", display = "srgb", tolerance = 1e-3 },
            { metric = "over_threshold", channels = "rgb", threshold = 1.5 / 255, tolerance = 0 },
        },
        display = {
            { metric = "flip", channels = "rgb", display = "srgb", tolerance = 1e-3 },
            { metric = "over_threshold", channels = "rgb", threshold = 1.5 / 255, tolerance = 0 },
        },
    },
}

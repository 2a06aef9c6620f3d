-- Every pass of the golden shading pipeline, each resource with the metric that suits its data:
-- normals by angle, integer material ids exactly, 8-bit albedo by its LSB, HDR radiance by
-- relative error, the display image perceptually (FLIP) and by the share of pixels off by more
-- than one 8-bit step. The profile switches the pipeline's dither and jitter off.
--
-- Tolerances: the same bits for any thread count, vector width and AVX level; a host without
-- SSE4.1 (GALLIUM_OVERRIDE_CPU_CAPS=sse3) moves the HDR by 1e-8 on average and 0.055 % at
-- worst and leaves everything else as it is. The bounds are those of deferred_pipeline.lua.
return {
    doc = "analytic sphere on a checkered ground: G-buffer, HDR lighting, tone-mapped display image",
    pipeline = "tests/golden/pipelines/shading.lua",
    size = { 160, 120 },
    captures = {
        material = { metric = "exact" },
        normal = {
            { metric = "angular", channels = "rgb", tolerance = 0.05 },
            { metric = "rel_max", channels = "a", tolerance = 1e-3 },
        },
        albedo = { metric = "max_abs", tolerance = 1 / 255 },
        hdr = {
            { metric = "rel_mean", channels = "rgb", tolerance = 1e-5 },
            { metric = "rel_max", channels = "rgb", epsilon = 1e-2, tolerance = 5e-3 },
        },
        ldr = {
            { metric = "flip", channels = "rgb", display = "srgb", tolerance = 0.01 },
            { metric = "over_threshold", channels = "rgb", threshold = 1.5 / 255, tolerance = 0.02 },
            { metric = "psnr", channels = "rgb", tolerance = 45 },
        },
    },
    -- Any device family against the primary (lavapipe) goldens: an NVIDIA H200 measured FLIP
    -- 0.010-0.016 on the display images of the default pipeline; 0.05 stays well clear of that.
    cross_device = { ldr = { metric = "flip", channels = "rgb", display = "srgb", tolerance = 0.05 } },
}

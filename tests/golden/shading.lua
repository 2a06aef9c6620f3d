-- Every pass of the golden shading pipeline, each resource with the metric that suits its data:
-- normals by angle, integer material ids exactly, 8-bit albedo by its LSB, HDR radiance by
-- relative error, the display image perceptually (FLIP) and by the share of pixels off by more
-- than one 8-bit step. The profile switches the pipeline's dither and jitter off.
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
        albedo = { metric = "max_abs", tolerance = 0.002 },
        hdr = {
            { metric = "rel_mean", channels = "rgb", tolerance = 1e-4 },
            { metric = "rel_max", channels = "rgb", tolerance = 2e-3 },
        },
        ldr = {
            { metric = "flip", channels = "rgb", display = "srgb", tolerance = 1e-3 },
            { metric = "over_threshold", channels = "rgb", threshold = 1.5 / 255, tolerance = 0 },
        },
    },
}

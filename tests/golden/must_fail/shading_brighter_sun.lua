-- MUST FAIL (tests/golden/CMakeLists.txt checks that it does): the goldens of `shading` against
-- a render whose sun is 5 % brighter from the first frame on (set by the frame callback). The
-- G-buffer captures still match; the first divergent resource in pipeline order is `hdr`,
-- written by the `lighting` pass, and the display image `ldr` diverges after it.
return {
    doc = "deliberately perturbed: the sun 5 % brighter than in the goldens of 'shading'",
    pipeline = "tests/golden/pipelines/shading.lua",
    golden = "shading",
    size = { 160, 120 },
    frame = function(ctx) ctx.params.sun_intensity = 3 * 1.05 end,
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
}

-- TAA (scripts/post.lua, shaders/post/taa.frag) with its jitter on — the golden profile turns
-- `taa_jitter` off elsewhere; here the test sets it, and the Halton (2, 3) sequence is fixed, so
-- the frames are the same every run: the first frame unjittered, then 8 jittered ones resolved
-- into the history. The default scene at a size where its sphere rows alias.
return {
    doc = "TAA over 9 frames of the default scene (8 jittered): the resolved HDR and the display image",
    pipeline = "scripts/pipelines/deferred.lua",
    scene = "scripts/scenes/default.lua",
    camera = "main",
    size = { 160, 96 },
    frames = 9,
    params = { taa_jitter = true, antialiasing = "taa" },
    captures = {
        taa = {
            { metric = "rel_mean", channels = "rgb", tolerance = 1e-5 },
            { metric = "rel_max", channels = "rgb", epsilon = 1e-2, tolerance = 0.02 },
        },
        display = {
            { metric = "flip", channels = "rgb", display = "srgb", tolerance = 0.01 },
            { metric = "over_threshold", channels = "rgb", threshold = 1.5 / 255, tolerance = 0.02 },
        },
    },
    cross_device = { display = { metric = "flip", channels = "rgb", display = "srgb", tolerance = 0.05 } },
}

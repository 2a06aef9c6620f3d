-- A persistent resource accumulates over frames: after four frames of step 0.5 it holds 2.
-- rgba32f, so the golden is a float EXR.
return {
    doc = "tests/lua/scripts/persistent.lua after 4 frames",
    pipeline = "tests/lua/scripts/persistent.lua",
    size = { 16, 16 },
    frames = 4,
    captures = {
        output = { metric = "rel_max", tolerance = 0 },
    },
}

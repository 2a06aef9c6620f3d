-- The `disney` G-buffer (seed 000 tbl:2) filled through the generated pack code: the octahedral
-- normal compared by angle, materialId (GB0.a) exactly, the 8-bit targets by their LSB.
return {
    doc = "tests/lua/scripts/gbuffer.lua: one material packed into GB0..GB3",
    pipeline = "tests/lua/scripts/gbuffer.lua",
    size = { 16, 16 },
    captures = {
        GB0 = {
            { metric = "angular", channels = "rg", encoding = "oct_unorm", tolerance = 0.01 },
            { metric = "max_abs", channels = "b", tolerance = 0 },
            { metric = "exact", channels = "a" },
        },
        GB1 = { metric = "max_abs", tolerance = 0 },
        GB2 = { metric = "exact" },
        GB3 = { metric = "max_abs", tolerance = 0 },
    },
}

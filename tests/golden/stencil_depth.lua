-- Stencil- and depth-tested fullscreen passes against a cleared depth/stencil buffer: only the
-- passes whose test passes leave their colour (hit and near do; miss and far keep the clear).
return {
    doc = "tests/lua/scripts/stencil_depth.lua",
    pipeline = "tests/lua/scripts/stencil_depth.lua",
    size = { 16, 16 },
    captures = {
        hit = { metric = "exact" },
        miss = { metric = "exact" },
        near = { metric = "exact" },
        far = { metric = "exact" },
    },
}

-- What a pass that decodes the G-buffer reads: the render loop's targets and the depth's stencil,
-- the pixel's material identity (every material's pixels carry their own stencil value). Its
-- shader defines RG_GBUFFER_BINDING (the first of five bindings) before
-- `#include "gbuffer_pipeline.glsl"` and calls rgGBufferAt(pixel): the pixel decoded with its
-- material's layout (RgGBufferView: normal, smoothness, ... and `has`, the ones it holds).
--
--   local reader = require "gbuffer_reader"
--   rg.pass "my_pass" { kind = "fullscreen", shader = "my.frag", reads = reader.reads { "depth" }, ... }
local reader = {}

reader.targets = { "GB0", "GB1", "GB2", "GB3" }

-- The targets and { "depth", as = "stencil" }, then the entries of `more`.
function reader.reads(more)
    local reads = {}
    for _, t in ipairs(reader.targets) do reads[#reads + 1] = t end
    reads[#reads + 1] = { "depth", as = "stencil" }
    for _, r in ipairs(more or {}) do reads[#reads + 1] = r end
    return reads
end

return reader

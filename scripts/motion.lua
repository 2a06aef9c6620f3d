-- Each pixel's screen motion since the last frame, as a target the scene passes write while the
-- scene's nodes move (scene objects with a `path`, the library's dynamic meshes), and the way a
-- pass that reprojects a history of its own takes it.
--
--   local motion = require "motion"
--   motion.declare()                        -- the `motion` target (scripts/render_loop.lua does)
--   rg.pass "my_temporal" (motion.reads { kind = "fullscreen", shader = "...", reads = { ... } })
--
-- `motion` (rg16f, uv units: where the surface is now minus where it was, lib/motion.glsl's sign)
-- exists only while a node of the scene moves (only_when): where nothing moves, a pixel's motion
-- is the camera's alone, which a shader finds exactly from the depth (lib/motion.glsl rgMotion), so
-- no target is written or read and the passes lose RG_MOTION. A pass given to motion.reads reads it
-- as the sampler `motion` with RG_MOTION defined while it exists: the shader then takes the
-- surface's own motion where something was drawn (lib/motion.glsl rgClipMotion wrote it).
local rg = require "rg"

local motion = {}

function motion.declare()
    rg.resource "motion" { format = "rg16f",
        only_when = { scene = "motion", defines = { "RG_MOTION" } } }
    motion.target = "motion"
end

-- `pass` reading the motion target when the pipeline declared one (RG_MOTION while it exists);
-- as it was otherwise.
function motion.reads(pass)
    if not motion.target then return pass end
    pass.reads = pass.reads or {}
    table.insert(pass.reads, motion.target)
    pass.defines = pass.defines or {}
    pass.defines.RG_MOTION = true
    return pass
end

return motion

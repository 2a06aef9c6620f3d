-- The camera's draws chosen on the GPU for scenes of many draws: a compute pass culls every draw the
-- G-buffer draws against the camera's frustum, picks its level of detail and lists it in the
-- indirect command of its batch (the draws sharing a mesh and material), and the G-buffer pass
-- draws each material's commands with vkCmdDrawIndexedIndirectCount — the CPU records one draw per
-- material and pipeline whatever the scene's size, and no longer walks the draws each frame.
--
--   local culling = require "culling"
--   culling.declare()                     -- render_loop.lua does
--   rg.pass "gbuffer" (culling.gbuffer { kind = "scene", writes = { ... }, ... })
--
-- shaders/passes/camera_cull.comp, over the scene's `SceneDraws`: the same frustum test and
-- level-of-detail choice as the CPU's (lib/culling.glsl, passes/gpu_scene.cpp updateFrame), so the
-- image is the CPU path's but where two draws meet at exactly the same depth: the GPU draws by
-- material, batch and the order the culling listed the instances, the CPU front to back. Its buffers
-- exist only for a scene of at least `culling.min_draws` draws with `gpu_culling` on (only_when):
-- below that (the default scene's 53 draws, the 10 000-node city's 7 570), the CPU's choice and
-- front-to-back order cost less, and the G-buffer pass, without the reads, draws as before.
local rg = require "rg"

local culling = {}

-- From this many draws the G-buffer's draws are culled on the GPU. On lavapipe the CPU's front-to-back
-- order saves the G-buffer more than its walk costs in the project's city of 10 000 nodes (7 570
-- draws: gbuffer ~45 ms against ~55 on the GPU's order), and both are even at 100 000 (75 626
-- draws: ~46 either way, the CPU's recording 1.9 → 1.5 ms).
culling.min_draws = 16384
-- Work groups of 64 of the culling pass: each invocation takes every (64 × this)-th draw.
culling.groups = 256

-- Declares the parameters, the buffers (only_when: a scene of at least culling.min_draws draws,
-- gpu_culling on) and the passes; render_loop.lua calls it before its G-buffer pass, so a pipeline
-- that sets culling.min_draws before requiring render_loop chooses from when the GPU culls.
function culling.declare()
    if culling.declared then return end
    culling.declared = true
    rg.param "gpu_culling" { type = "boolean", default = true,
        doc = "the G-buffer's draws culled and batched on the GPU in scenes of at least " .. culling.min_draws .. " draws" }
    rg.param "frustum_culling" { type = "boolean", default = true,
        doc = "with gpu_culling: drop the draws outside the camera's frustum (off: every draw drawn, to compare)" }

    local when = { scene = "draws:" .. culling.min_draws, param = "gpu_culling" }
    rg.buffer "camera_draws" { size = 20, scene_count = "camera_batches", count_bytes = 4 * 20, only_when = when,
        doc = "the G-buffer's draws: an indirect command per camera batch (a mesh and material) and level of detail (VkDrawIndexedIndirectCommand)" }
    rg.buffer "camera_instances" { size = 4, scene_count = "draws", count_bytes = 4 * 4, only_when = when,
        doc = "the draws each of camera_draws' commands draws: a draw index per instance, a region per level of detail" }
    rg.buffer "camera_draw_counts" { size = 4, scene_count = "materials", count_bytes = 4, only_when = when,
        doc = "per material, how many of its run of camera_draws' commands the G-buffer draws" }
    rg.pass "camera_cull_clear" { kind = "clear", writes = { "camera_draws", "camera_draw_counts" } }
    rg.pass "camera_cull" {
        kind = "compute", shader = "passes/camera_cull.comp", groups = { culling.groups, 1, 1 },
        switches = { frustum_culling = "RG_CAMERA_CULL" },
        writes = { { "camera_draws", as = "storage_rw" }, { "camera_instances", as = "storage" },
                   { "camera_draw_counts", as = "storage_rw" } },
    }
end

-- `pass` (a G-buffer `scene` pass's declaration) drawing the culling pass's commands while they
-- exist: it reads the three buffers and names them (the `scene` kind's indirect, indirect_count).
function culling.gbuffer(pass)
    if not culling.declared then return pass end
    pass.reads = pass.reads or {}
    table.insert(pass.reads, { "camera_draws", as = "indirect" })
    table.insert(pass.reads, { "camera_draw_counts", as = "indirect" })
    table.insert(pass.reads, { "camera_instances", as = "storage" })
    pass.indirect, pass.indirect_count = "camera_draws", "camera_draw_counts"
    return pass
end

return culling

-- The camera's draws chosen on the GPU for scenes of many draws, in two phases (occlusion culling,
-- Haar & Aaltonen 2015): a compute pass lists the draws that showed last frame and meet the camera's
-- frustum in the indirect commands of their batches (the draws sharing a mesh and material) at the
-- level of detail the camera takes, gbuffer_early draws them, camera_hiz builds the pyramid of the
-- farthest depth they left, and camera_cull tests every draw in the frustum against it: the ones
-- that may show and were not drawn first are drawn by the G-buffer pass over gbuffer_early's
-- targets, and each draw's answer is kept for the next frame. Each phase draws each camera run's
-- commands (the materials of one pipeline, cull mode, texture set and window of parameters) with
-- vkCmdDrawIndexedIndirectCount — the CPU records one draw per run whatever the scene's size, and
-- no longer walks the draws each frame.
--
--   local culling = require "culling"
--   culling.declare()                     -- render_loop.lua does
--   rg.pass "gbuffer" (culling.gbuffer { kind = "scene", writes = { ... }, ... })
--
-- shaders/passes/camera_cull.comp, over the scene's `SceneDraws`: the same frustum test and
-- level-of-detail choice as the CPU's (lib/culling.glsl, passes/gpu_scene.cpp cullForCamera), and an
-- occlusion test that drops a draw only where everything drawn over the pixels it can cover is
-- nearer than all of it — so the image is the CPU path's but where two draws meet at exactly the
-- same depth: the GPU draws by phase, material, batch and the order the culling listed the
-- instances, the CPU front to back. Its buffers exist only for a scene of at least
-- `culling.min_draws` draws, on a device that draws from instance lists the GPU wrote
-- (`gpu_draws`), with `gpu_culling` on (only_when), the first phase's and the pyramid with
-- `occlusion_culling` on too: below that (the default scene's 53 draws), the CPU's choice and
-- front-to-back order cost less, and the G-buffer pass, without the reads, draws as before.
local rg = require "rg"

local culling = {}

-- From this many draws the G-buffer's draws are culled on the GPU. On lavapipe at 1280×720 the
-- project's city from its street draws its G-buffer in ~21 + 2 (camera_hiz) ms at 2 000 nodes
-- (1 522 draws) against ~47 on the CPU's path, ~29 against ~52 at 10 000; the default scene's 53
-- draws, little hidden, ~25 against ~19.
culling.min_draws = 1024
-- Work groups of 64 of the culling pass: each invocation takes every (64 × this)-th draw.
culling.groups = 256

-- Declares the parameters, the buffers (only_when: a scene of at least culling.min_draws draws
-- the device can draw from GPU-written lists, gpu_culling on; the first phase's and the pyramid
-- also occlusion_culling on) and the first phase's culling;
-- render_loop.lua calls it before its G-buffer pass, so a pipeline that sets culling.min_draws
-- before requiring render_loop chooses from when the GPU culls.
function culling.declare()
    if culling.declared then return end
    culling.declared = true
    rg.param "gpu_culling" { type = "boolean", default = true,
        doc = "the G-buffer's draws culled and batched on the GPU in scenes of at least " .. culling.min_draws .. " draws" }
    rg.param "frustum_culling" { type = "boolean", default = true,
        doc = "with gpu_culling: drop the draws outside the camera's frustum, and those hidden (occlusion_culling) (off: every draw drawn, to compare)" }
    rg.param "occlusion_culling" { type = "boolean", default = true,
        doc = "with gpu_culling: two phases — last frame's visible draws first, then the rest tested against the depth they drew (off: the frustum alone)" }

    local when = { scene = { "draws:" .. culling.min_draws, "gpu_draws" }, param = "gpu_culling" }
    culling.occluding = { scene = when.scene, param = { "gpu_culling", "occlusion_culling" } }
    rg.buffer "camera_draws" { size = 20, scene_count = "camera_batches", count_bytes = 4 * 20, only_when = when,
        doc = "the G-buffer's draws: an indirect command per camera batch (a mesh and material) and level of detail (VkDrawIndexedIndirectCommand)" }
    rg.buffer "camera_instances" { size = 4, scene_count = "draws", count_bytes = 4 * 4, only_when = when,
        doc = "the draws each of camera_draws' commands draws: a draw index per instance, a region per level of detail" }
    rg.buffer "camera_draw_counts" { size = 4, scene_count = "camera_runs", count_bytes = 4, only_when = when,
        doc = "per camera run (the materials of one pipeline, cull mode, texture set and window of parameters), how many of its range of camera_draws' commands the G-buffer draws" }
    rg.buffer "camera_early_draws" { size = 20, scene_count = "camera_batches", count_bytes = 4 * 20, only_when = culling.occluding,
        doc = "the first phase's commands (gbuffer_early): the draws that showed last frame, as camera_draws" }
    rg.buffer "camera_early_counts" { size = 4, scene_count = "camera_runs", count_bytes = 4, only_when = culling.occluding,
        doc = "per camera run, how many of its range of camera_early_draws' commands gbuffer_early draws" }
    rg.buffer "camera_early_instances" { size = 4, scene_count = "draws", count_bytes = 4 * 4, only_when = culling.occluding,
        doc = "the draws each of camera_early_draws' commands draws, as camera_instances" }
    rg.buffer "camera_visible" { size = 4, scene_count = "draws", count_bytes = 4, persistent = true, only_when = culling.occluding,
        doc = "per draw, whether it showed in the last frame (1; 0 not; 2 while this frame's first phase drew it): the first phase draws those" }
    rg.resource "camera_hiz" { format = "r32f", scale = 1 / 8, mips = "full",
        only_when = { scene = when.scene, param = culling.occluding.param, defines = { "RG_OCCLUSION" } },
        doc = "the farthest depth gbuffer_early drew, per 8 × 8 pixels and up a pyramid of mips" }
    rg.pass "camera_early_clear" { kind = "clear", writes = { "camera_early_draws", "camera_early_counts" } }
    rg.pass "camera_cull_early" {
        kind = "compute", shader = "passes/camera_cull.comp", groups = { culling.groups, 1, 1 },
        switches = { frustum_culling = "RG_CAMERA_CULL" }, defines = { RG_CULL_EARLY = true }, only_when = culling.occluding,
        bind = { camera_draws = "camera_early_draws", camera_draw_counts = "camera_early_counts",
                 camera_instances = "camera_early_instances" },
        writes = { { "camera_visible", as = "storage_rw" },
                   { "camera_early_draws", as = "storage_rw" }, { "camera_early_instances", as = "storage" },
                   { "camera_early_counts", as = "storage_rw" } },
    }
end

-- A shallow copy of table `t` (nil: an empty one).
local function copy(t)
    local c = {}
    for k, v in pairs(t or {}) do c[k] = v end
    return c
end

-- Adds `reads`' entries to the pass declaration `pass`'s reads.
local function read(pass, reads)
    pass.reads = pass.reads or {}
    for _, r in ipairs(reads) do table.insert(pass.reads, r) end
end

-- `pass` (a G-buffer `scene` pass's declaration, writing `depth`) drawing the culling passes'
-- commands while they exist: it reads camera_draws, camera_draw_counts and camera_instances and
-- names them (the `scene` kind's indirect, indirect_count). In two phases (occlusion_culling) a
-- copy of it, gbuffer_early, draws the first phase's commands and the pyramid of its depth is
-- built (camera_hiz) before camera_cull chooses the rest, which `pass` draws over the first
-- phase's targets (its writes load while gbuffer_early runs). Declares the passes it needs, so
-- call it where the G-buffer pass is declared.
function culling.gbuffer(pass, depth)
    if not culling.declared then return pass end
    if pass.insert then
        error("culling.gbuffer: declare the G-buffer pass where it runs, not with insert (its first phase and culling go before it)", 2)
    end
    depth = depth or "depth"
    local early = copy(pass)
    early.bind, early.reads = copy(pass.bind), copy(pass.reads)
    early.bind.camera_instances = "camera_early_instances"
    read(early, { { "camera_early_draws", as = "indirect" }, { "camera_early_counts", as = "indirect" },
                  { "camera_early_instances", as = "storage" } })
    early.indirect, early.indirect_count, early.only_when = "camera_early_draws", "camera_early_counts", culling.occluding
    rg.pass "gbuffer_early" (early)
    rg.pass "camera_hiz" {
        kind = "compute", shader = "passes/hiz.comp", reads = { depth }, writes = { { "camera_hiz", as = "storage" } },
        bind = { depth = depth, hiz = "camera_hiz" }, per_mip = true, filter = "nearest", defines = { RG_HIZ_FARTHEST = true },
    }
    rg.pass "camera_cull_clear" { kind = "clear", writes = { "camera_draws", "camera_draw_counts" } }
    rg.pass "camera_cull" {
        kind = "compute", shader = "passes/camera_cull.comp", groups = { culling.groups, 1, 1 },
        switches = { frustum_culling = "RG_CAMERA_CULL" }, defines = { RG_OCCLUSION = true },
        reads = { { "camera_hiz", as = "sampled" } },
        writes = { { "camera_draws", as = "storage_rw" }, { "camera_instances", as = "storage" },
                   { "camera_draw_counts", as = "storage_rw" }, { "camera_visible", as = "storage_rw" } },
        filter = "nearest",
    }
    local writes = {}
    for _, w in ipairs(pass.writes or {}) do
        local t = type(w) == "table" and copy(w) or { w }
        t.load = t.load or "gbuffer_early"
        table.insert(writes, t)
    end
    pass.writes = writes
    read(pass, { { "camera_draws", as = "indirect" }, { "camera_draw_counts", as = "indirect" },
                 { "camera_instances", as = "storage" } })
    pass.indirect, pass.indirect_count = "camera_draws", "camera_draw_counts"
    return pass
end

return culling

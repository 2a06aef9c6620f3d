#version 460
// The camera's culling on the GPU (scripts/culling.lua; the G-buffer pass's `indirect`): each draw
// the G-buffer draws (RgDraw.camera.x: its camera batch + 1 — the draws sharing a mesh and
// material) whose world box meets the camera's frustum joins the indirect command of its batch at
// the level of detail the camera takes — the coarsest whose error spans at most a pixel at the
// nearest depth of its box: the test and the choice GpuScene::cullForCamera makes on the CPU.
//
// camera_draws (cleared first): per batch and level an indexed indirect command (batch · 4 +
// level), its instance count grown by an atomic add; every draw that joins writes the same index
// range and first instance. camera_instances: per level a region of one slot per draw, each
// batch's run at its first slot (RgDraw.camera.y): instance k of a command is the draw at
// firstInstance + k (scene.vert with RG_CAMERA_INSTANCES). camera_draw_counts (cleared first):
// per camera run (RgDraw.info.y: the materials of one pipeline, cull mode, texture set and window,
// GpuScene::CameraRun) how many of its commands the G-buffer draws — a run's batches are
// consecutive, so its commands are one range from its first batch's (RgDraw.camera.w: the draw's
// batch's first command within that run), and the count is one past the last that has an instance
// (vkCmdDrawIndexedIndirectCount; commands before it without one draw nothing). Without
// RG_CAMERA_CULL (culling off, to compare) every draw joins.
//
// Two-phase occlusion culling (Haar & Aaltonen 2015): camera_visible holds, per draw, whether it
// showed last frame (1). RG_CULL_EARLY (the pass camera_cull_early, its commands bound to
// camera_early_draws and camera_early_counts): the draws in the frustum that showed last frame,
// which gbuffer_early draws, each marked 2 (drawn first). RG_OCCLUSION (camera_cull, after camera_hiz built the farthest-depth
// pyramid of what gbuffer_early drew): every draw in the frustum is tested against the pyramid
// (rgBoxMayShow), its answer kept in camera_visible for the next frame, and the draws that may
// show but were not drawn first join — the G-buffer draws them over the first phase's. A draw
// drawn first that no longer shows leaves the next frame's first phase. (The first phase's
// instances go to camera_early_instances, bound as camera_instances.) The image is that of no
// occlusion test: a draw is skipped only where everything drawn over its pixels is nearer than
// all of it.
#define RG_SCENE_DRAWS 1
#include "lib/scene.glsl"
#include "lib/culling.glsl"

#ifndef RG_CAMERA_CULL
#define RG_CAMERA_CULL 1
#endif

layout(local_size_x = 64) in;
layout(set = 0, binding = 0, std430) buffer camera_draws { DrawIndexedIndirect command[]; } commands;
layout(set = 0, binding = 1, std430) writeonly buffer camera_instances { uint draw[]; } instances;
layout(set = 0, binding = 2, std430) buffer camera_draw_counts { uint count[]; } counts;
#if defined(RG_CULL_EARLY) || defined(RG_OCCLUSION)
layout(set = 0, binding = 3, std430) buffer camera_visible { uint visible[]; } visibility;
#endif
#ifdef RG_OCCLUSION
layout(set = 0, binding = 4) uniform sampler2D camera_hiz;
#endif

void main() {
    const uint batches = uint(commands.command.length()) / 4u;
    const uint slots = uint(instances.draw.length()) / 4u;  // draws per level's region
    const vec4 planes[6] = rgFrustumPlanes(camera.unjitteredViewProj);
    // Each invocation takes every (invocations)-th draw: lavapipe ends a shader's loops after
    // 65 535 iterations in all (DESIGN §8), so no invocation walks many.
    const uint invocations = gl_NumWorkGroups.x * gl_WorkGroupSize.x;
    for (uint d = gl_GlobalInvocationID.x; d < sceneDraws.header.x; d += invocations) {
        const RgDraw draw = sceneDraws.draw[d];
        const uint batch = draw.camera.x;
        if (batch == 0u || batch > batches || draw.camera.y + draw.camera.z > slots ||
            draw.info.y >= uint(counts.count.length()))
            continue;
#if RG_CAMERA_CULL
        const bool inFrustum = rgBoxMeetsFrustum(planes, draw.boxMin.xyz, draw.boxMax.xyz);
#else
        const bool inFrustum = true;
#endif
#if defined(RG_CULL_EARLY)
        if (!inFrustum || visibility.visible[d] == 0u) continue;
        visibility.visible[d] = 2u;  // drawn first: the second phase reads it so
#elif defined(RG_OCCLUSION)
        const bool drawnFirst = visibility.visible[d] == 2u;
        const bool shows = inFrustum && (RG_CAMERA_CULL == 0 ||
            rgBoxMayShow(camera_hiz, camera.unjitteredViewProj, draw.boxMin.xyz, draw.boxMax.xyz));
        visibility.visible[d] = shows ? 1u : 0u;
        if (drawnFirst || !shows) continue;
#else
        if (!inFrustum) continue;
#endif
        const uint level = rgCameraLevel(draw, 1.0);
        const uint k = (batch - 1u) * 4u + level;
        const uint first = level * slots + draw.camera.y;
        rgJoinCommand(k, first, draw, d, level);
        atomicMax(counts.count[draw.info.y], draw.camera.w + level + 1u);
    }
}

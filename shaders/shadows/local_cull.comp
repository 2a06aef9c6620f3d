#version 460
// Caster culling for the local lights' shadow views (scripts/shadows.lua's `local_cull`), per
// instance, as shadows/cascade_cull.comp does for the sun's cascades: each caster whose world box
// meets view v's frustum (lib/shadows.glsl ShadowViews, written each frame by the scene) joins, in
// that view, the indirect draw of its shadow batch (the casters sharing its mesh and cull mode) at
// the level of detail the camera draws it with — what passes/gpu_scene_lights.cpp's walk over
// every view and caster did on the CPU.
//
// local_shadow_draws (cleared first): per view slot, batch and level an indexed indirect command
// ((v · batches + batch − 1) · 4 + level), its instance count grown by an atomic add (the first
// caster to join writes the rest of it).
// local_shadow_instances: per view slot and level a region of one slot per caster, each batch's
// run at its first slot (RgDraw.shadow.y). RG_LOCAL_VIEWS view slots: the layers of the map.
#define RG_SCENE_DRAWS 1
#define RG_SHADOW_VIEWS 1
#include "lib/scene.glsl"
#include "lib/shadows.glsl"
#include "lib/culling.glsl"

#ifndef RG_LOCAL_VIEWS
#define RG_LOCAL_VIEWS 6
#endif

layout(local_size_x = 64) in;
layout(set = 0, binding = 0, std430) buffer local_shadow_draws { DrawIndexedIndirect command[]; } commands;
layout(set = 0, binding = 1, std430) writeonly buffer local_shadow_instances { uint draw[]; } instances;

void main() {
    const uint batches = uint(commands.command.length()) / uint(RG_LOCAL_VIEWS * 4);
    const uint slots = uint(instances.draw.length()) / uint(RG_LOCAL_VIEWS * 4);  // casters per region
    const uint views = min(rgShadowViews.count.x, uint(RG_LOCAL_VIEWS));
    // Each invocation takes every (invocations)-th draw: lavapipe ends a shader's loops after
    // 65 535 iterations in all (DESIGN §8), so no invocation walks many.
    const uint invocations = gl_NumWorkGroups.x * gl_WorkGroupSize.x;
    vec4 planes[RG_LOCAL_VIEWS][6];
    for (uint v = 0u; v < views; ++v) planes[v] = rgFrustumPlanes(rgShadowViews.view[v].viewProj);
    for (uint d = gl_GlobalInvocationID.x; d < sceneDraws.header.x; d += invocations) {
        const RgDraw draw = sceneDraws.draw[d];
        const uint batch = draw.shadow.x;
        if (batch == 0u || batch > batches || draw.shadow.y + draw.shadow.z > slots) continue;
        // The camera's level of detail, as the CPU's walk drew it — with 1 % to spare, as the
        // cascades' (lib/culling.glsl): rounding may leave a caster coarser than its receiver,
        // never finer (a finer caster would stand in front of it by up to the coarser one's error).
        const uint level = rgCameraLevel(draw, 1.01);
        for (uint v = 0u; v < views; ++v) {
            if (!rgBoxMeetsFrustum(planes[v], draw.boxMin.xyz, draw.boxMax.xyz)) continue;
            const uint k = (v * batches + batch - 1u) * 4u + level;
            const uint first = (v * 4u + level) * slots + draw.shadow.y;
            rgJoinCommand(k, first, draw, d, level);
        }
    }
}

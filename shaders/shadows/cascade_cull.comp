#version 460
// Caster culling for the sun's cascades (seed 002 §4.10.4, #13: "shadow casters outside a light's
// frustum are not drawn"), per instance: each caster (a draw that casts shadows) whose world box
// meets a cascade's orthographic box across the light joins, in that cascade, the indirect draw
// of its shadow batch (the casters sharing its mesh and cull mode: GpuScene::shadowBatches) at
// the level of detail it takes there — the coarsest the cascade's texels cannot tell from the
// full one, never finer than the camera's. Depth is not culled: a caster nearer the sun than the
// slice still shadows it (sun_cascades.comp spans the scene's bounds along the light).
//
// sun_shadow_draws (cleared first): per cascade, per batch, per level an indexed indirect command
// ((cascade · batches + batch − 1) · 4 + level); its instance count grows by an atomic add, and the
// first caster to join writes its index range and first instance. sun_shadow_instances: per
// cascade and level a region of one slot per caster, each batch's run at its first slot
// (RgDraw.shadow.y): instance k of a command is the draw at firstInstance + k. The shadow passes
// draw every command (shadow.vert with RG_SHADOW_INSTANCES): batches × levels draws a cascade
// instead of one per caster.
#define RG_SCENE_DRAWS 1
#include "lib/scene.glsl"
#include "lib/shadows.glsl"
#include "lib/culling.glsl"

layout(local_size_x = 64) in;
layout(set = 0, binding = 0, std430) readonly buffer sun_cascades { RgCascades c; } cascades;
layout(set = 0, binding = 1, std430) buffer sun_shadow_draws { DrawIndexedIndirect command[]; } commands;
layout(set = 0, binding = 2, std430) writeonly buffer sun_shadow_instances { uint draw[]; } instances;

bool boxMeetsCascade(vec3 lo, vec3 hi, mat4 m) {
    vec2 cmin = vec2(1e30), cmax = vec2(-1e30);
    for (int k = 0; k < 8; ++k) {
        vec3 p = vec3((k & 1) != 0 ? hi.x : lo.x, (k & 2) != 0 ? hi.y : lo.y, (k & 4) != 0 ? hi.z : lo.z);
        vec2 xy = (m * vec4(p, 1.0)).xy;  // orthographic: w = 1
        cmin = min(cmin, xy);
        cmax = max(cmax, xy);
    }
    return all(lessThanEqual(cmin, vec2(1.0))) && all(greaterThanEqual(cmax, vec2(-1.0)));
}

void main() {
    const uint batches = uint(commands.command.length()) / uint(RG_CASCADES * 4);
    const uint slots = uint(instances.draw.length()) / uint(RG_CASCADES * 4);  // casters per region
    const int cascadesInUse = int(cascades.c.info.x + 0.5);
    // Each invocation takes every (invocations)-th draw: lavapipe ends a shader's loops after
    // 65 535 iterations in all (DESIGN §8), so no invocation walks many.
    const uint invocations = gl_NumWorkGroups.x * gl_WorkGroupSize.x;
    for (uint d = gl_GlobalInvocationID.x; d < sceneDraws.header.x; d += invocations) {
        RgDraw draw = sceneDraws.draw[d];
        const uint batch = draw.shadow.x;
        if (batch == 0u || batch > batches || draw.shadow.y + draw.shadow.z > slots) continue;
        const uint cameraLod = rgCameraLevel(draw, 1.01);
        for (int c = 0; c < min(cascadesInUse, RG_CASCADES); ++c) {
            if (!boxMeetsCascade(draw.boxMin.xyz, draw.boxMax.xyz, cascades.c.viewProj[c])) continue;
            // The coarsest level of detail whose error stays within a texel of this cascade — and
            // never finer than the one the camera sees the draw with: a coarser level lies inside
            // the finer ones (its vertices are theirs), so a receiver drawn coarser than its own
            // caster would sit behind it by up to the error and shadow itself.
            uint level = cameraLod;
            for (uint l = level + 1u; l < min(draw.info.w, 4u); ++l)
                if (draw.lodError[l] <= cascades.c.texelWorld[c]) level = l;
            const uint k = (uint(c) * batches + batch - 1u) * 4u + level;
            const uint first = (uint(c) * 4u + level) * slots + draw.shadow.y;
            rgJoinCommand(k, first, draw, d, level);
        }
    }
}

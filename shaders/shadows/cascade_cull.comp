#version 460
// Caster culling for the sun's cascades (seed 002 §4.10.4, #13: "shadow casters outside a light's
// frustum are not drawn"): for each cascade and each draw of the scene, the indirect draw command
// the shadow pass issues for it — the draw's index range, one instance when its world box meets the
// cascade's orthographic box across the light, none when it lies beside it (or is blended). Depth
// is not culled: a caster nearer the sun than the slice still shadows it (sun_cascades.comp spans
// the scene's bounds along the light). Commands are laid out cascade by cascade, each cascade
// holding the same number of slots (the buffer's commands / RG_CASCADES); the scene pass draws
// directly the draws beyond them.
#define RG_SCENE_DRAWS 1
#include "lib/scene.glsl"
#include "lib/shadows.glsl"

layout(local_size_x = 64) in;
layout(set = 0, binding = 0, std430) readonly buffer sun_cascades { RgCascades c; } cascades;
struct DrawIndexedIndirect { uint indexCount, instanceCount, firstIndex; int vertexOffset; uint firstInstance; };
layout(set = 0, binding = 1, std430) writeonly buffer sun_shadow_draws { DrawIndexedIndirect command[]; } commands;

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
    uint slots = uint(commands.command.length()) / uint(RG_CASCADES);
    uint count = min(sceneDraws.header.x, slots);
    int cascadesInUse = int(cascades.c.info.x + 0.5);
    for (uint d = gl_LocalInvocationIndex; d < count; d += 64u) {
        RgDraw draw = sceneDraws.draw[d];
        for (int c = 0; c < RG_CASCADES; ++c) {
            bool visible = draw.info.z != 0u && c < cascadesInUse && boxMeetsCascade(draw.boxMin.xyz, draw.boxMax.xyz, cascades.c.viewProj[c]);
            commands.command[uint(c) * slots + d] = DrawIndexedIndirect(floatBitsToUint(draw.boxMax.w), visible ? 1u : 0u,
                                                                        floatBitsToUint(draw.boxMin.w), int(draw.info.x), 0u);
        }
    }
}

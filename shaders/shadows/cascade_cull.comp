#version 460
// Caster culling for the sun's cascades (seed 002 §4.10.4, #13: "shadow casters outside a light's
// frustum are not drawn"): for each cascade and each draw of the scene, the indirect draw command
// the shadow pass issues for it — the index range of the draw's coarsest level of detail the
// cascade's texels cannot tell from the full one, one instance when its world box meets the
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

// The level of detail the camera's passes draw the draw with (GpuScene::updateFrame): the coarsest
// whose error spans at most a pixel at the nearest view depth of its box — here with 1 % to spare,
// so that rounding never leaves it finer than the CPU's choice.
uint cameraLevel(RgDraw draw) {
    vec3 forward = -vec3(camera.view[0][2], camera.view[1][2], camera.view[2][2]);
    float nearest = 1e30;
    for (int k = 0; k < 8; ++k) {
        vec3 p = vec3((k & 1) != 0 ? draw.boxMax.x : draw.boxMin.x, (k & 2) != 0 ? draw.boxMax.y : draw.boxMin.y,
                      (k & 4) != 0 ? draw.boxMax.z : draw.boxMin.z);
        nearest = min(nearest, dot(p - camera.position.xyz, forward));
    }
    bool orthographic = rgCameraOrthographic();
    float pixelsPerMetre = abs(camera.proj[1][1]) * camera.viewport.y * 0.5 / (orthographic ? 1.0 : max(nearest, 1e-6));
    uint level = 0u;
    if (orthographic || nearest > 0.0)
        for (uint l = 1u; l < min(draw.info.w, 4u); ++l)
            if (draw.lodError[l] * pixelsPerMetre <= 1.01) level = l;
    return level;
}

void main() {
    uint slots = uint(commands.command.length()) / uint(RG_CASCADES);
    uint count = min(sceneDraws.header.x, slots);
    int cascadesInUse = int(cascades.c.info.x + 0.5);
    for (uint d = gl_LocalInvocationIndex; d < count; d += 64u) {
        RgDraw draw = sceneDraws.draw[d];
        for (int c = 0; c < RG_CASCADES; ++c) {
            bool visible = draw.info.z != 0u && c < cascadesInUse && boxMeetsCascade(draw.boxMin.xyz, draw.boxMax.xyz, cascades.c.viewProj[c]);
            // The coarsest level of detail whose error stays within a texel of this cascade — and
            // never finer than the one the camera sees the draw with: a coarser level lies inside
            // the finer ones (its vertices are theirs), so a receiver drawn coarser than its own
            // caster would sit behind it by up to the error and shadow itself.
            uint level = cameraLevel(draw);
            for (uint l = level + 1u; l < min(draw.info.w, 4u); ++l)
                if (draw.lodError[l] <= cascades.c.texelWorld[c]) level = l;
            commands.command[uint(c) * slots + d] = DrawIndexedIndirect(draw.lodCount[level], visible ? 1u : 0u,
                                                                        draw.lodFirst[level], int(draw.info.x), 0u);
        }
    }
}

#version 460
// Scene draws: the world transform from push constants — or, for a run of draws drawn as one
// instanced draw (passes/scene_pass.cpp), from the scene's per-draw transforms through its
// instance list — the camera from the scene. With RG_MOTION (a pass that writes the motion
// target, scripts/render_loop.lua) also where the vertex is by this frame's unjittered camera and
// where it was by the last frame's camera and world matrix (a draw that moves is always drawn
// through the list, which holds that matrix; a single draw has not moved).
#include "lib/scene.glsl"

layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in vec4 inTangent;
layout(location = 3) in vec2 inUv0;
layout(location = 4) in vec2 inUv1;
layout(location = 5) in vec4 inColor;  // COLOR_0 (white without)

layout(location = 0) out vec3 worldPosition;
layout(location = 1) out vec3 worldNormal;
layout(location = 2) out vec4 worldTangent;
layout(location = 3) out vec2 uv0;
layout(location = 4) out vec2 uv1;
layout(location = 6) out vec4 vertexColor;
layout(location = 5) out vec2 lightmapUv;  // the node's square of the scene's lightmap atlas
#ifdef RG_CAMERA_INSTANCES
layout(location = 9) flat out uint materialIndex;  // each instance's (lib/material.glsl)
#endif
#ifdef RG_MOTION
layout(location = 7) out vec4 motionNow;     // clip position, this frame's unjittered camera
layout(location = 8) out vec4 motionBefore;  // clip position on the last frame
#endif

// 128 bytes, the push-constant size every Vulkan device has. All zeros: an instanced run.
layout(push_constant) uniform Draw {
    mat4 world;
    vec4 normalMatrix[3];  // inverse transpose of world's upper 3x3, its columns
    vec4 lightmapRect;     // atlas uv = uv1 * xy + zw (0: no lightmap)
} draw;

// Per draw: world's four columns, the normal matrix's three (the first's w: the material's index in
// its window, uint bits: lib/material.glsl), the lightmap rect, the last frame's world (RG_TRANSFORM_WORDS, passes/gpu_scene.h).
#ifndef RG_TRANSFORMS_BINDING
#define RG_TRANSFORMS_BINDING 34
#endif
layout(set = RG_CAMERA_SET, binding = RG_TRANSFORMS_BINDING, std430) readonly buffer SceneTransforms { vec4 t[]; } sceneTransforms;
// This frame's instance lists: the draw of each instance, at firstInstance + its index — the
// scene's, which the CPU writes, or with RG_CAMERA_INSTANCES (the G-buffer's draws culled on the
// GPU: shaders/passes/camera_cull.comp) those the culling pass wrote.
#ifdef RG_CAMERA_INSTANCES
layout(set = 0, binding = 39, std430) readonly buffer camera_instances { uint draw[]; } sceneInstances;
#else
layout(set = RG_CAMERA_SET, binding = RG_TRANSFORMS_BINDING + 1, std430) readonly buffer SceneInstances { uint draw[]; } sceneInstances;
#endif

void main() {
    mat4 world = draw.world;
    mat3 normalMatrix = mat3(draw.normalMatrix[0].xyz, draw.normalMatrix[1].xyz, draw.normalMatrix[2].xyz);
    vec4 lightmapRect = draw.lightmapRect;
    uint materialBits = 0u;
#ifdef RG_MOTION
    mat4 previousWorld = draw.world;
#endif
    if (draw.world[3][3] == 0.0) {  // no affine transform has it: an instanced run
        uint base = uint(RG_TRANSFORM_WORDS) * sceneInstances.draw[gl_InstanceIndex];
        world = mat4(sceneTransforms.t[base], sceneTransforms.t[base + 1u], sceneTransforms.t[base + 2u], sceneTransforms.t[base + 3u]);
        normalMatrix = mat3(sceneTransforms.t[base + 4u].xyz, sceneTransforms.t[base + 5u].xyz, sceneTransforms.t[base + 6u].xyz);
        materialBits = floatBitsToUint(sceneTransforms.t[base + 4u].w);
        lightmapRect = sceneTransforms.t[base + 7u];
#ifdef RG_MOTION
        previousWorld = mat4(sceneTransforms.t[base + 8u], sceneTransforms.t[base + 9u], sceneTransforms.t[base + 10u], sceneTransforms.t[base + 11u]);
#endif
    }
    vec4 p = world * vec4(inPosition, 1.0);
    worldPosition = p.xyz;
    worldNormal = normalMatrix * inNormal;
    worldTangent = vec4(mat3(world) * inTangent.xyz, inTangent.w);
    uv0 = inUv0;
    uv1 = inUv1;
    vertexColor = inColor;
#ifdef RG_CAMERA_INSTANCES
    materialIndex = materialBits;
#endif
    lightmapUv = inUv1 * lightmapRect.xy + lightmapRect.zw;
    gl_Position = camera.viewProj * p;
#ifdef RG_MOTION
    motionNow = camera.unjitteredViewProj * p;
    motionBefore = camera.previousViewProj * (previousWorld * vec4(inPosition, 1.0));
#endif
}

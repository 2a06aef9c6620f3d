#version 460
// Scene draws: world transform from push constants, the camera from the scene.
#include "lib/scene.glsl"

layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in vec4 inTangent;
layout(location = 3) in vec2 inUv0;
layout(location = 4) in vec2 inUv1;

layout(location = 0) out vec3 worldPosition;
layout(location = 1) out vec3 worldNormal;
layout(location = 2) out vec4 worldTangent;
layout(location = 3) out vec2 uv0;
layout(location = 4) out vec2 uv1;
layout(location = 5) out vec2 lightmapUv;  // the node's square of the scene's lightmap atlas

// 128 bytes, the push-constant size every Vulkan device has.
layout(push_constant) uniform Draw {
    mat4 world;
    vec4 normalMatrix[3];  // inverse transpose of world's upper 3x3, its columns
    vec4 lightmapRect;     // atlas uv = uv1 * xy + zw (0: no lightmap)
} draw;

void main() {
    vec4 p = draw.world * vec4(inPosition, 1.0);
    worldPosition = p.xyz;
    worldNormal = mat3(draw.normalMatrix[0].xyz, draw.normalMatrix[1].xyz, draw.normalMatrix[2].xyz) * inNormal;
    worldTangent = vec4(mat3(draw.world) * inTangent.xyz, inTangent.w);
    uv0 = inUv0;
    uv1 = inUv1;
    lightmapUv = inUv1 * draw.lightmapRect.xy + draw.lightmapRect.zw;
    gl_Position = camera.viewProj * p;
}

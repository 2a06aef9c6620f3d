#version 460
// Local light probe capture (scripts/probes.lua's `probe_capture`: the `scene` kind with
// capture = true): each draw into layer `draw.layer.x` = 6 · probe + face of the capture target,
// seen from the probe's position through that cube face — the projection whose pixel (x, y)
// looks along rgCubeDirection(face, (x, y) / size), as the distant probe's cube is laid out
// (shaders/ibl/env_cube.comp), with depth over [near, far].
#include "lib/scene.glsl"
#include "lib/environment.glsl"
#include "lib/probes.glsl"

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
layout(location = 5) flat out vec3 eye;

layout(push_constant) uniform Draw {
    mat4 world;
    vec4 layer;  // x: the layer being drawn (6 · probe + face)
} draw;

const float kNear = 0.02, kFar = 2000.0;  // metres

void main() {
    vec4 p = draw.world * vec4(inPosition, 1.0);
    worldPosition = p.xyz;
    worldNormal = transpose(inverse(mat3(draw.world))) * inNormal;
    worldTangent = vec4(mat3(draw.world) * inTangent.xyz, inTangent.w);
    uv0 = inUv0;
    uv1 = inUv1;
    vertexColor = inColor;
    uint layer = uint(draw.layer.x + 0.5);
    uint face = layer % 6u;
    eye = rgProbes.probe[layer / 6u].positionShape.xyz;
    // The face's forward axis and the axes along which its s and t grow (unit at the face's edge).
    vec3 F = rgCubeDirection(face, vec2(0.5));
    vec3 U = rgCubeDirection(face, vec2(1.0, 0.5)) * sqrt(2.0) - F;
    vec3 V = rgCubeDirection(face, vec2(0.5, 1.0)) * sqrt(2.0) - F;
    vec3 r = p.xyz - eye;
    float w = dot(r, F);
    gl_Position = vec4(dot(r, U), dot(r, V), kFar / (kFar - kNear) * (w - kNear), w);
}

#version 460
// Shadow-map draws (the `scene` kind with shadow = true): every layer of the map at once
// (multiview), layer gl_ViewIndex from the matrix of cascade gl_ViewIndex; depth only.
#extension GL_EXT_multiview : require
#include "lib/shadows.glsl"

layout(location = 0) in vec3 inPosition;

layout(push_constant) uniform Draw {
    mat4 world;
    mat4 normalMatrix;
} draw;

layout(set = 0, binding = 0, std430) readonly buffer sun_cascades { RgCascades c; } cascades;

void main() {
    gl_Position = cascades.c.viewProj[gl_ViewIndex] * (draw.world * vec4(inPosition, 1.0));
}

#version 460
// The scene's points and lines (passes/scene_pass_lines.cpp): the node's world transform from
// push constants, the camera from the scene; one pixel wide.
#include "lib/scene.glsl"

layout(location = 0) in vec3 inPosition;
layout(location = 3) in vec2 inUv0;
layout(location = 4) in vec2 inUv1;
layout(location = 5) in vec4 inColor;  // COLOR_0 (white without)

layout(location = 0) out vec2 uv0;
layout(location = 1) out vec2 uv1;
layout(location = 2) out vec4 vertexColor;

layout(push_constant) uniform Draw {
    mat4 world;
} draw;

void main() {
    uv0 = inUv0;
    uv1 = inUv1;
    vertexColor = inColor;
    gl_Position = camera.viewProj * (draw.world * vec4(inPosition, 1.0));
    gl_PointSize = 1.0;
}

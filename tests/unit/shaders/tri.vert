#version 460

layout(set = 0, binding = 0, std140) uniform Camera {
    mat4 viewProj;  // offset 0
    vec4 eye;       // offset 64
} camera;

layout(push_constant) uniform Push {
    mat4 model;  // offset 0
} pc;

layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec2 inUv;
layout(location = 0) out vec2 outUv;

void main() {
    outUv = inUv;
    gl_Position = camera.viewProj * pc.model * vec4(inPosition, 1.0);
}

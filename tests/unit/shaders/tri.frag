#version 460

layout(set = 0, binding = 0, std140) uniform Camera {
    mat4 viewProj;
    vec4 eye;
} camera;
layout(set = 0, binding = 1) uniform sampler2D albedo;

layout(push_constant) uniform Push {
    layout(offset = 64) vec4 color;  // after the vertex stage's mat4
} pc;

layout(location = 0) in vec2 inUv;
layout(location = 0) out vec4 outColor;
layout(location = 1) out vec4 outNormal;

void main() {
    outColor = texture(albedo, inUv) * pc.color + camera.eye * 0.0;
    outNormal = vec4(0.0, 0.0, 1.0, 0.0);
}

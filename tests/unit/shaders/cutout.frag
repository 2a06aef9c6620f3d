#version 460
// An alpha-tested fragment shader: it can discard, so a pass drawn over every pixel still leaves
// some of its targets as they were (test_shader.cpp).
layout(set = 0, binding = 1) uniform sampler2D albedo;
layout(location = 0) in vec2 inUv;
layout(location = 0) out vec4 outColor;

void main() {
    vec4 c = texture(albedo, inUv);
    if (c.a < 0.5) discard;
    outColor = c;
}

#version 460

// set 0 binding 0 is the Camera uniform buffer in tri.vert: a layout conflict.
layout(set = 0, binding = 0) uniform sampler2D shadowMap;

layout(location = 0) in vec2 inUv;
layout(location = 0) out vec4 outColor;

void main() { outColor = texture(shadowMap, inUv); }

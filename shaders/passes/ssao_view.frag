#version 460
// The `ssao` debug view: the screen-space ambient occlusion (scripts/ao.lua), white open, black closed.
layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 color;
layout(set = 0, binding = 0) uniform sampler2D ssao;

void main() { color = vec4(vec3(texelFetch(ssao, ivec2(gl_FragCoord.xy), 0).r), 1.0); }

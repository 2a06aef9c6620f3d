#version 460
// Second stage of the built-in test graph: reads the pattern texel for texel and maps it,
// out = (g, r, 1 - b, 1) * scale, with `scale` from the Params uniform block.
layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 color;
layout(set = 0, binding = 0) uniform sampler2D pattern;
layout(set = 0, binding = 1) uniform Params { float scale; } params;

void main() {
    vec4 c = texelFetch(pattern, ivec2(gl_FragCoord.xy), 0);
    color = vec4(c.g, c.r, 1.0 - c.b, 1.0) * params.scale;
}

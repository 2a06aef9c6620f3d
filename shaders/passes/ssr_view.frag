#version 460
// The `ssr` debug view: the screen-space reflection's colour times its confidence (tone-mapped
// crudely: x / (1 + x) of the pre-exposed value); `ssr_confidence`: the confidence alone.
layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 color;
layout(set = 0, binding = 0) uniform sampler2D ssr;
layout(set = 0, binding = 1) uniform Params { float view; } params;

void main() {
    vec4 r = texelFetch(ssr, ivec2(gl_FragCoord.xy), 0);
    color = params.view < 0.5 ? vec4(r.rgb * r.a / (1.0 + r.rgb * r.a), 1.0) : vec4(vec3(r.a), 1.0);
}

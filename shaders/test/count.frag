#version 460
// Counts frames through a history (tests/lua/scripts/history.lua): this frame's `count` is the
// last frame's (`count_history`, zeros when empty) plus Params.step, plus 100 with RG_COUNT_HUNDRED
// (a compiled-in switch: changing it rebuilds the pass).
layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 color;
layout(set = 0, binding = 0) uniform sampler2D count_history;
layout(set = 0, binding = 1) uniform Params { float step; } params;

void main() {
    float last = texelFetch(count_history, ivec2(gl_FragCoord.xy), 0).r;
#if RG_COUNT_HUNDRED
    last += 100.0;
#endif
    color = vec4(last + params.step, 0.0, 0.0, 1.0);
}

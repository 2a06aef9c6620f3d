#version 460
// The `switches` example of scripts/README.md: Params.tint, halved when the pass compiles its
// `mode` parameter in as RG_MODE 1 ("half").
layout(location = 0) out vec4 color;
layout(set = 0, binding = 0) uniform Params { vec4 tint; } params;

void main() {
#if RG_MODE == 1
    color = params.tint * 0.5;
#else
    color = params.tint;
#endif
}

#version 460
// The `ssr` debug view: the screen-space reflection's colour times its confidence, pre-exposed as
// the frame is and tone-mapped crudely (x / (1 + x)); `ssr_confidence`: the confidence alone;
// `reflection` (view 2, `reflection` bound as `ssr`): the composed reflection's colour alone.
#include "lib/exposure.glsl"
layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 color;
layout(set = 0, binding = 0) uniform sampler2D ssr;
layout(set = 0, binding = 1) uniform Params { float view; float initial_ev100; } params;
layout(set = 0, binding = 2, std430) readonly buffer exposure { RgExposureState state; } ex;

void main() {
    vec4 r = texture(ssr, uv);  // `ssr` is at half resolution: bilinear, as the composition reads it
    vec3 c = r.rgb * r.a * rgPreExposure(ex.state, params.initial_ev100);
    if (params.view > 1.5) c = r.rgb * rgPreExposure(ex.state, params.initial_ev100);
    color = params.view < 0.5 || params.view > 1.5 ? vec4(c / (1.0 + c), 1.0) : vec4(vec3(r.a), 1.0);
}

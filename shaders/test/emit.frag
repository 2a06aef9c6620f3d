#version 460
// A surface of uniform luminance (Params.luminance, cd/m²) written pre-exposed, as every HDR
// pass writes it; `highlight` adds a disc of much higher luminance (e.g. a sun disk, 1.6e9 cd/m²).
#include "lib/exposure.glsl"

layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 color;
layout(set = 0, binding = 0, std430) readonly buffer exposure { RgExposureState state; } ex;
layout(set = 0, binding = 1) uniform Params {
    float luminance;
    float highlight;
    float initial_ev100;
} params;

void main() {
    float L = params.luminance;
    if (params.highlight > 0.0 && length(uv - vec2(0.5)) < 0.05) L = params.highlight;
    color = vec4(vec3(L * rgPreExposure(ex.state, params.initial_ev100)), 1.0);
}

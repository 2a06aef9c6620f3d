#version 460
// A hard, aliased diagonal edge of luminance Params.luminance (pre-exposed), for FXAA tests.
#include "lib/exposure.glsl"

layout(location = 0) out vec4 color;
layout(set = 0, binding = 0, std430) readonly buffer exposure { RgExposureState state; } ex;
layout(set = 0, binding = 1) uniform Params { float luminance; float initial_ev100; } params;

void main() {
    vec2 p = gl_FragCoord.xy;
    float L = p.x > 0.7 * p.y + 10.0 ? params.luminance : params.luminance * 0.01;
    color = vec4(vec3(L * rgPreExposure(ex.state, params.initial_ev100)), 1.0);
}

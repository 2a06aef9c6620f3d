#version 460
// A ramp of luminance and hue across the image (Params.luminance times 0.05 … 2.05 along x, the
// colour varying along y), written pre-exposed as every HDR pass writes it: post-chain tests.
#include "lib/exposure.glsl"

layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 color;
layout(set = 0, binding = 0, std430) readonly buffer exposure { RgExposureState state; } ex;
layout(set = 0, binding = 1) uniform Params {
    float luminance;
    float initial_ev100;
} params;

void main() {
    vec3 L = params.luminance * (0.05 + 2.0 * uv.x) * vec3(1.0, 0.6 + 0.8 * uv.y, 0.5);
    color = vec4(L * rgPreExposure(ex.state, params.initial_ev100), 1.0);
}

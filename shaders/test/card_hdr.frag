#version 460
// The test card as HDR: the pattern's colours scaled to Params.card_luminance (cd/m²) and
// written pre-exposed, so the camera and post chain have something physical to expose.
#include "lib/exposure.glsl"

layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 color;
layout(set = 0, binding = 0) uniform sampler2D card;
layout(set = 0, binding = 1, std430) readonly buffer exposure { RgExposureState state; } ex;
layout(set = 0, binding = 2) uniform Params { float card_luminance; float initial_ev100; } params;

void main() {
    vec3 c = texture(card, uv).rgb;
    color = vec4(vec3(c.g, c.r, 1.0 - c.b) * params.card_luminance * rgPreExposure(ex.state, params.initial_ev100), 1.0);
}

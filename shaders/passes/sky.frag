#version 460
// The background where nothing was drawn (depth test "equal 1" against the cleared depth): a
// simple physical sky of luminance Params.sky_luminance at the zenith, brighter towards the
// horizon, darker below it, pre-exposed.
#include "lib/scene.glsl"
#include "lib/exposure.glsl"

layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 color;
layout(set = 0, binding = 0, std430) readonly buffer exposure { RgExposureState state; } ex;
layout(set = 0, binding = 1) uniform Params { float sky_luminance; float initial_ev100; } params;

void main() {
    vec3 far = rgWorldPosition(uv, 1.0);
    vec3 d = normalize(far - camera.position.xyz);
    float up = d.y;
    vec3 zenith = vec3(0.25, 0.45, 1.0), horizon = vec3(0.85, 0.9, 1.0), ground = vec3(0.18, 0.16, 0.14);
    vec3 sky = up > 0.0 ? mix(horizon * 1.6, zenith, pow(up, 0.6)) : mix(horizon * 0.6, ground * 0.4, pow(-up, 0.4));
    color = vec4(sky * params.sky_luminance * rgPreExposure(ex.state, params.initial_ev100), 1.0);
}

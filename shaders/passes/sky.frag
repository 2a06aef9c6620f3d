#version 460
// The background where nothing was drawn (depth test against the cleared depth): the scene's
// environment (lib/environment.glsl — the same equirectangular image of nits the distant light
// probe is filtered from), pre-exposed; black without one. The sun is a light, not part of the
// environment (seed 002 §4.9.1.1: strong sources are removed from the probe): its disk is not drawn.
#include "lib/scene.glsl"
#include "lib/exposure.glsl"
#include "lib/environment.glsl"

layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 color;
layout(set = 0, binding = 0, std140) uniform exposure { RgExposureState state; } ex;  // a uniform block: read once per block of pixels
layout(set = 0, binding = 1) uniform Params { float initial_ev100; } params;
layout(set = 0, binding = 2) uniform sampler2D SceneEnvironment;

void main() {
    // Through the pixel: from the eye to the far plane; an orthographic camera looks along its axis.
    vec3 d = rgCameraOrthographic() ? -rgViewDirection(vec3(0.0)) : normalize(rgWorldPosition(uv, 1.0) - camera.position.xyz);
    vec3 sky = textureLod(SceneEnvironment, rgEquirectUv(d), 0.0).rgb;
    color = vec4(sky * rgPreExposure(ex.state, params.initial_ev100), 1.0);
}

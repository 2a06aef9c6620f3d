#version 460
// Deferred lighting of the standard material (seed 000 §3.1, §4): the G-buffer of the `disney`
// layout, every light of the scene (punctual lights with the windowed inverse-square falloff and
// smooth angular attenuation of lst:4, the sun as a directional light in lux), emissive, written
// as pre-exposed luminance. Runs only on the pixels of its stencil class (the pass's stencil test).
#include "lib/scene.glsl"
#include "lib/brdf.glsl"
#include "lib/exposure.glsl"
#include "gbuffer_disney.glsl"

layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 color;
layout(set = 0, binding = 0) uniform sampler2D GB0;
layout(set = 0, binding = 1) uniform sampler2D GB1;
layout(set = 0, binding = 2) uniform sampler2D GB2;
layout(set = 0, binding = 3) uniform sampler2D GB3;
layout(set = 0, binding = 4) uniform sampler2D depth;
layout(set = 0, binding = 5, std430) readonly buffer exposure { RgExposureState state; } ex;
layout(set = 0, binding = 6) uniform Params { float initial_ev100; } params;

// lst:4 — windowed inverse-square falloff; distances below 1 cm are clamped.
float smoothDistanceAtt(float squaredDistance, float invSqrAttRadius) {
    float factor = squaredDistance * invSqrAttRadius;
    float smoothFactor = clamp(1.0 - factor * factor, 0.0, 1.0);
    return smoothFactor * smoothFactor;
}
float getDistanceAtt(vec3 unnormalizedLightVector, float invSqrAttRadius) {
    float sqrDist = dot(unnormalizedLightVector, unnormalizedLightVector);
    float attenuation = 1.0 / max(sqrDist, 0.01 * 0.01);
    return invSqrAttRadius > 0.0 ? attenuation * smoothDistanceAtt(sqrDist, invSqrAttRadius) : attenuation;
}
float getAngleAtt(vec3 normalizedLightVector, vec3 lightDir, float lightAngleScale, float lightAngleOffset) {
    float cd = dot(lightDir, normalizedLightVector);
    float attenuation = clamp(cd * lightAngleScale + lightAngleOffset, 0.0, 1.0);
    return attenuation * attenuation;
}

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    GBuffer_disney g = unpackGBuffer_disney(texelFetch(GB0, p, 0), texelFetch(GB1, p, 0), texelFetch(GB2, p, 0),
                                            texelFetch(GB3, p, 0));
    vec3 position = rgWorldPosition(uv, texelFetch(depth, p, 0).r);
    vec3 V = normalize(camera.position.xyz - position);
    vec3 N = g.normal;
    // §3.2.1: metals take their f0 from the base colour, dielectrics 0.16 · reflectance².
    vec3 diffuseColor = g.baseColor * (1.0 - g.metalMask);
    vec3 f0 = mix(vec3(rgDielectricF0(g.reflectance)), g.baseColor, g.metalMask);
    float linearRoughness = 1.0 - g.smoothness;

    vec3 luminance = g.emissive;
    uint count = lights.count.x;
    for (uint i = 0u; i < count; ++i) {
        RgLight light = lights.light[i];
        vec3 L;
        vec3 illuminance;  // lux, per colour channel, before the BRDF's NdotL
        if (light.positionType.w > 1.5) {  // the sun: illuminance perpendicular to its rays
            L = -normalize(light.directionRadius.xyz);
            illuminance = light.intensity.rgb;
        } else {
            vec3 toLight = light.positionType.xyz - position;
            L = normalize(toLight);
            float att = getDistanceAtt(toLight, light.directionRadius.w);
            att *= getAngleAtt(-L, normalize(light.directionRadius.xyz), light.params.x, light.params.y);
            illuminance = light.intensity.rgb * att;  // cd / d² = lux
        }
        luminance += rgStandardBrdf(N, V, L, diffuseColor, f0, linearRoughness) * illuminance;
    }
    color = vec4(luminance * rgPreExposure(ex.state, params.initial_ev100), 1.0);
}

// The light loop shared by every lighting path and the forward pass: for light i of the scene,
// the illuminance it delivers at a point (lux, per colour channel, on a surface facing it) and
// the direction towards it. Seed 000 §4: punctual lights with the windowed inverse-square
// falloff and smooth angular attenuation (lst:4), the sun as a directional light in lux.
#ifndef RG_LIGHTING_GLSL
#define RG_LIGHTING_GLSL

#include "lib/scene.glsl"
#include "lib/brdf.glsl"

// lst:4 — windowed inverse-square falloff; distances below 1 cm are clamped. (The listing's
// max(sqrtDist, …) means the squared distance: 0.01² is 1 cm squared.)
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

vec3 rgLightIlluminance(uint i, vec3 position, out vec3 L) {
    RgLight light = lights.light[i];
    if (light.positionType.w > 1.5) {  // the sun: illuminance perpendicular to its rays
        L = -normalize(light.directionRadius.xyz);
        return light.intensity.rgb;
    }
    vec3 toLight = light.positionType.xyz - position;
    L = normalize(toLight);
    float att = getDistanceAtt(toLight, light.directionRadius.w);
    att *= getAngleAtt(-L, normalize(light.directionRadius.xyz), light.params.x, light.params.y);
    return light.intensity.rgb * att;  // cd / d² = lux
}

uint rgLightCount() { return lights.count.x; }

#endif

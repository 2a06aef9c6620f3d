#include "punctual.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace rg::lighting {

namespace {
float saturate(float x) { return std::clamp(x, 0.0f, 1.0f); }
}  // namespace

float smoothDistanceAtt(float squaredDistance, float invSqrAttRadius) {
    // seed 000 lst:4 / eq:26 (n = 4): windowed so the falloff reaches 0 with zero slope.
    const float factor = squaredDistance * invSqrAttRadius;
    const float smoothFactor = saturate(1.0f - factor * factor);
    return smoothFactor * smoothFactor;
}

float getDistanceAtt(glm::vec3 unnormalizedLightVector, float invSqrAttRadius) {
    // seed 000 lst:4 with eq:14's 1 cm minimum distance.
    const float sqrDist = glm::dot(unnormalizedLightVector, unnormalizedLightVector);
    const float attenuation = 1.0f / std::max(sqrDist, kPunctualMinDistance * kPunctualMinDistance);
    return invSqrAttRadius > 0.0f ? attenuation * smoothDistanceAtt(sqrDist, invSqrAttRadius)
                                  : attenuation;
}

float getAngleAtt(glm::vec3 normalizedLightVector, glm::vec3 lightDir, float lightAngleScale,
                  float lightAngleOffset) {
    // seed 000 lst:4: a linear ramp in cos θ between the outer and inner cone, squared to smooth it.
    const float cd = glm::dot(lightDir, normalizedLightVector);
    const float attenuation = saturate(cd * lightAngleScale + lightAngleOffset);
    return attenuation * attenuation;
}

AngleScaleOffset spotAngleScaleOffset(float innerAngle, float outerAngle) {
    // seed 000 lst:4, "computed on the CPU".
    const float cosOuter = std::cos(outerAngle);
    const float cosInner = std::cos(innerAngle);
    const float scale = 1.0f / std::max(0.001f, cosInner - cosOuter);
    return {scale, -cosOuter * scale};
}

double frustumSolidAngle(double openingA, double openingB) {
    // seed 000 tbl:9 (frustum): the solid angle of a right rectangular pyramid.
    return 4.0 * std::asin(std::sin(openingA * 0.5) * std::sin(openingB * 0.5));
}

double frustumIntensityFromLumens(double lumens, double openingA, double openingB) {
    return lumens / frustumSolidAngle(openingA, openingB);  // tbl:9
}

double coneSolidAngle(double openingAngle) {
    constexpr double kPi = 3.14159265358979323846;
    return 2.0 * kPi * (1.0 - std::cos(openingAngle * 0.5));  // eq:16, tbl:9 (spot)
}

}  // namespace rg::lighting

// Punctual lights on the CPU (seed 000 §4.4): the C++ twins of the lst:4 attenuation functions in
// shaders/lib/lighting.glsl (same names, float arithmetic), the CPU side of the spot cone, and the
// frustum light of tbl:9 that graph/core/light_units.h does not have. Point and spot lm → cd and
// E = I cosθ / d² live in graph/core/light_units.h (rg::lights) and are not repeated here.
// Units: distances in metres, intensity in cd, illuminance in lux, angles in radians.
#pragma once

#include <glm/vec3.hpp>

namespace rg::lighting {

// Punctual lights are 1 cm spheres as far as the falloff is concerned (eq:14): closer points see
// the intensity divided by 1 cm², never by zero.
inline constexpr float kPunctualMinDistance = 0.01f;

// lst:4 — the window (1 − (d²/r²)²)², saturated: 1 at the light, 0 at the attenuation radius r,
// zero slope there (eq:26 with n = 4). invSqrAttRadius = 1 / r².
float smoothDistanceAtt(float squaredDistance, float invSqrAttRadius);

// lst:4 — 1 / max(d², 0.01²) times the window; multiplied by the intensity (cd) it gives the
// illuminance (lux) on a surface facing the light. As in lighting.glsl, invSqrAttRadius ≤ 0 means
// "no radius": the plain inverse square law. (The seed's listing writes max(sqrtDist, 0.01·0.01);
// 0.01² is 1 cm squared, so it is the squared distance that is clamped.)
float getDistanceAtt(glm::vec3 unnormalizedLightVector, float invSqrAttRadius);

// lst:4 — smooth cone attenuation: saturate(cd · scale + offset)², cd the cosine between lightDir
// and normalizedLightVector. lighting.glsl passes −L (light → surface) and the spot's direction; the
// seed passes L and a "lightForward" that points back at the light — the same cosine.
float getAngleAtt(glm::vec3 normalizedLightVector, glm::vec3 lightDir, float lightAngleScale,
                  float lightAngleOffset);

// lst:4's CPU part: scale = 1 / max(0.001, cos inner − cos outer), offset = −cos outer · scale.
// innerAngle and outerAngle are half-angles of the cone (from its axis), radians.
struct AngleScaleOffset {
    float scale = 0.0f;
    float offset = 1.0f;  // scale 0, offset 1: no cone (a point light)
};
AngleScaleOffset spotAngleScaleOffset(float innerAngle, float outerAngle);

// tbl:9 — frustum light, lm → cd: I = Φ / (4 arcsin(sin(θa/2) sin(θb/2))), θa and θb the full
// opening angles of the pyramid (radians). The denominator is the pyramid's solid angle (sr),
// 2π for θa = θb = π (a hemisphere).
double frustumSolidAngle(double openingA, double openingB);
double frustumIntensityFromLumens(double lumens, double openingA, double openingB);

// tbl:9 / eq:16 written with the seed's full opening angle θ_outer: the cone's solid angle
// 2π (1 − cos(θ_outer / 2)). rg::lights::spotIntensityFromLumens(Φ, θ_outer / 2, true) is the
// conversion itself (it takes the half-angle).
double coneSolidAngle(double openingAngle);

}  // namespace rg::lighting

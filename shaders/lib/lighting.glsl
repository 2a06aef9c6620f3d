// The light loop shared by every lighting path and the forward pass. For light i of the scene and
// a shaded point, rgEvaluateLight gives what the diffuse lobe receives — the illuminance, with the
// horizon handled for area lights — and where the specular lobe sees the light — the
// representative point, with the energy normalisation of the widened lobe:
//   point, spot   seed 000 lst:4 (windowed inverse square, smooth cone), eq:27 / lst:5 (IES)
//   sun           seed 000 lst:6: diffuse as a directional light, specular towards the closest
//                 point of the sun's disk
//   sphere, disk  seed 000 lst:10 (the merged form, horizon included)
//   rect, tube    seed 002 §4.7.2.5, §4.7.2.6 (structured sampling: 4 corners + centre × Ω)
//   specular      seed 002 §4.7.5: Karis' representative point (the light's point closest to the
//                 reflection ray, here the area dominant direction), energy normalised.
// With area_lights = "ltc" (scripts/lighting.lua; Lights.count.y = 1) the area lights' GGX lobe is
// instead integrated over the light by linearly transformed cosines (lib/ltc.glsl), and the
// diffuse lobe sees the exact cosine-weighted form factor (the same integral with M = identity;
// the sphere keeps lst:10, exact), both horizon clipped, with the Disney term averaged over the
// light's visible part (lib/ltc.glsl's rgHorizonDisney); rgStandardLighting then takes the
// integrated lobes. (An LTC fitted to the Disney diffuse lobe was measured worse than the form
// factor × Disney at the light's mean direction: 1.2–1.5 % against 0.2–0.6 % facing.)
// The CPU twins are graph/lighting's area_lights.h, punctual.h and ies.h; tests/gpu/test_lights.cpp
// compares the two. Intensities arrive converted (graph/lighting/light_table.cpp): cd, lux or cd/m².
#ifndef RG_LIGHTING_GLSL
#define RG_LIGHTING_GLSL

#include "lib/scene.glsl"
#include "lib/brdf.glsl"
#include "lib/light_tiles.glsl"
#include "lib/shadows.glsl"

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
// §4.4: the same window ends area lights at their range; its criterion is radial (the distance to
// the light's centre), a trade-off the seed accepts for tubes and rectangles.
float rgRangeWindow(float squaredDistance, float invSqrAttRadius) {
    return invSqrAttRadius > 0.0 ? smoothDistanceAtt(squaredDistance, invSqrAttRadius) : 1.0;
}

vec3 rgSafeNormalize(vec3 v, vec3 fallback) {
    float l2 = dot(v, v);
    return l2 > 1e-20 ? v * inversesqrt(l2) : fallback;
}

// ---- IES profiles (seed 000 §4.5, lst:5) -------------------------------------------------------

// The profile (I / I_max, in [0, 1]) of `light` towards the shaded point; L is the unit vector from
// the point to the light. Light space: +z is the light's direction (the profile's nadir), +x its
// axis (horizontal angle 0°), +y = z × x. The bilinear lookup is written out (repeat in θ,
// clamp-to-edge in cos φ, texel centres): the arithmetic of graph/lighting's sampleIesTexture.
float rgIesAttenuation(RgLight light, vec3 L) {
#if !RG_SCENE_IES
    return 1.0;
#endif
    if (light.intensity.a < 0.0) return 1.0;
    vec3 z = light.directionRange.xyz, x = light.axis.xyz;
    vec3 y = cross(z, x);
    vec3 d = vec3(dot(-L, x), dot(-L, y), dot(-L, z));  // lst:5: worldToLight · −L
    float phiCoord = d.z * 0.5 + 0.5;
    float theta = abs(d.x) + abs(d.y) > 0.0 ? atan(d.y, d.x) : 0.0;  // atan(0, 0) is undefined in GLSL
    float thetaCoord = theta * (0.5 / RG_PI);
    int width = int(lightTables.header.x), height = int(lightTables.header.y);
    float fx = thetaCoord * float(width) - 0.5, fy = phiCoord * float(height) - 0.5;
    float x0 = floor(fx), y0 = floor(fy);
    float wx = fx - x0, wy = fy - y0;
    int i0 = int(mod(x0, float(width)));  // GLSL's % is undefined for negative operands
    int i1 = (i0 + 1) % width;
    int j0 = clamp(int(y0), 0, height - 1), j1 = clamp(int(y0) + 1, 0, height - 1);
    uint base = uint(light.intensity.a + 0.5) * uint(width * height);
    float t00 = lightTables.iesTexels[base + uint(j0 * width + i0)], t10 = lightTables.iesTexels[base + uint(j0 * width + i1)];
    float t01 = lightTables.iesTexels[base + uint(j1 * width + i0)], t11 = lightTables.iesTexels[base + uint(j1 * width + i1)];
    return mix(mix(t00, t10, wx), mix(t01, t11, wx), wy);
}

// ---- Diffuse area lights -----------------------------------------------------------------------

// seed 000 lst:10: sphere and disk in one form, horizon included. cosTheta: unclamped cosine between
// the normal and the direction to the light's centre; sinSigmaSqr: sin² of the half-angle the light
// subtends (sphere r²/d², disk facing the point r²/(r² + d²)). Returns the illuminance of a light of
// luminance 1 cd/m² (lux).
float illuminanceSphereOrDisk(float cosTheta, float sinSigmaSqr) {
    float sinTheta = sqrt(max(0.0, 1.0 - cosTheta * cosTheta));
    float illuminance = 0.0;
    if (cosTheta * cosTheta > sinSigmaSqr) {
        illuminance = RG_PI * sinSigmaSqr * clamp(cosTheta, 0.0, 1.0);
    } else {
        float x = sqrt(1.0 / sinSigmaSqr - 1.0);  // d / r for the disk
        float y = -x * (cosTheta / sinTheta);      // sinTheta > 0 here: cos²θ ≤ sin²σ < 1
        float sinThetaSqrtY = sinTheta * sqrt(max(0.0, 1.0 - y * y));
        illuminance = (cosTheta * acos(clamp(y, -1.0, 1.0)) - x * sinThetaSqrtY) * sinSigmaSqr + atan(sinThetaSqrtY / x);
    }
    return max(illuminance, 0.0);
}

// seed 002 §4.7.2.5, rectangleSolidAngle: the solid angle (sr) of the quad v0 v1 v2 v3 (corners
// relative to the shaded point, in order around it), Girard's Σ angles − 2π.
float rgRectangleSolidAngle(vec3 v0, vec3 v1, vec3 v2, vec3 v3) {
    vec3 n0 = normalize(cross(v0, v1)), n1 = normalize(cross(v1, v2));
    vec3 n2 = normalize(cross(v2, v3)), n3 = normalize(cross(v3, v0));
    float g0 = acos(clamp(dot(-n0, n1), -1.0, 1.0)), g1 = acos(clamp(dot(-n1, n2), -1.0, 1.0));
    float g2 = acos(clamp(dot(-n2, n3), -1.0, 1.0)), g3 = acos(clamp(dot(-n3, n0), -1.0, 1.0));
    return max(g0 + g1 + g2 + g3 - 2.0 * RG_PI, 0.0);
}

// seed 002 §4.7.2.5, structured sampling of the light's shape: Ω × the mean of ⟨n·l⟩ over the four
// corners and the centre (vectors relative to the shaded point); the clamped cosines handle the horizon.
float rgStructuredQuadIlluminance(vec3 N, float solidAngle, vec3 centre, vec3 p0, vec3 p1, vec3 p2, vec3 p3) {
    return solidAngle * 0.2 *
           (clamp(dot(normalize(p0), N), 0.0, 1.0) + clamp(dot(normalize(p1), N), 0.0, 1.0) +
            clamp(dot(normalize(p2), N), 0.0, 1.0) + clamp(dot(normalize(p3), N), 0.0, 1.0) +
            clamp(dot(normalize(centre), N), 0.0, 1.0));
}

#include "lib/ltc.glsl"

// ---- The lights that reach every pixel ---------------------------------------------------------

// The first RG_LIGHTS_WINDOW lights again, as a uniform block over the same buffer (the scene binds
// `LightsWindow` to the head of its Lights buffer: 16 + 204 · 80 bytes, within the 16 KiB every
// Vulkan device allows a uniform block). Lavapipe reads a uniform block at a constant offset once
// for all the pixels it shades together, but a storage buffer lane by lane in a fragment shader
// (its first lane may be inactive there): the default frame's two lights' 20-odd floats cost
// lighting_standard ~1 ms at 1280×720 as storage reads.
#ifndef RG_LIGHTS_WINDOW_BINDING
#define RG_LIGHTS_WINDOW_BINDING 24
#endif
#define RG_LIGHTS_WINDOW 204  // passes/gpu_scene.h kLightsWindow
layout(set = RG_CAMERA_SET, binding = RG_LIGHTS_WINDOW_BINDING, std140) uniform LightsWindow {
    uvec4 count;
    RgLight light[RG_LIGHTS_WINDOW];
} lightsWindow;

// Light i's data, for an i the compiler knows (the unrolled loop over the lights that reach every
// pixel, materials/standard_shading.glsl): from the uniform window when it holds it, rgLight
// otherwise — the other side folds away. (A varying i would pay for both reads.) Copied
// member by member: the two blocks' RgLight types differ in layout, which SPIR-V cannot store as one.
RgLight rgGlobalLight(uint i) {
    if (i >= uint(RG_LIGHTS_WINDOW)) return rgLight(i);
    RgLight light;
    light.positionType = lightsWindow.light[i].positionType;
    light.directionRange = lightsWindow.light[i].directionRange;
    light.intensity = lightsWindow.light[i].intensity;
    light.params = lightsWindow.light[i].params;
    light.axis = lightsWindow.light[i].axis;
    return light;
}

// ---- Specular area lights (seed 002 §4.7.5) ----------------------------------------------------

// The area-light dominant direction: normalize(lerp(N, R, 1 − roughness)), roughness = α.
vec3 rgSpecularDominantDirArea(vec3 N, vec3 R, float alpha) { return normalize(mix(N, R, 1.0 - alpha)); }

// Karis (the reference of §4.7.5): moving the light to its representative point widens the lobe
// as if α became α' = saturate(α + ½ · subtended angle); GGX's normalisation 1/(π α²) then asks
// for (α / α')² for a sphere. Per widened dimension: α / α'. `angle` ≈ half extent / distance.
// Not in the seeds; kept by measurement (rgraph accuracy): without it a glossy metal under an area
// light gets +280 % to +3000 % of the reference's energy, a glossy dielectric +10 % to +330 %.
float rgLobeWidening(float alpha, float angle) { return alpha / clamp(alpha + 0.5 * clamp(angle, 0.0, 1.0), 0.0, 1.0); }

// The point of a plane (through `centre`, normal n; vectors relative to the shaded point) the ray
// R meets, or where it passes closest to the centre when it runs away from the plane's front.
vec3 rgRayOnPlane(vec3 centre, vec3 n, vec3 R) {
    float denom = dot(R, n);
    float t = denom < -1e-4 ? dot(centre, n) / denom : -1.0;
    vec3 hit = t > 0.0 ? R * t : dot(centre, R) * R;
    return hit - dot(hit - centre, n) * n;  // back on the plane
}

// seed 000 lst:9: a disk light's cone, a spot's angle attenuation seen from the cone's apex behind
// the disk (r / tan θ_outer back along its direction, axis.w): applied to its illuminance as is,
// "without regard for realism". A disk without a cone has scale 0, offset 1: 1.
float rgDiskCone(RgLight light, vec3 P) {
    vec3 dir = light.directionRange.xyz;
    vec3 apex = light.positionType.xyz - dir * light.axis.w;
    return getAngleAtt(-rgSafeNormalize(apex - P, -dir), dir, light.params.x, light.params.y);
}

// ---- One light at one point --------------------------------------------------------------------

// What light i gives a point: the diffuse lobe sees `diffuseIlluminance` (lux, per channel; the
// cosine and the horizon already in it) from direction Ld; the specular lobe sees
// `specularIlluminance` (lux on a surface facing the light, before ⟨n·Ls⟩) from the representative
// direction Ls, times `specularNormalisation` (1 for punctual lights). See rgStandardLighting.
// An area light under the LTC model also gives its GGX lobe integrated over its shape, at the
// roughness it was evaluated with: the lobe's luminance is specularLtc · (f0 · ltcAlbedo.x + f90 ·
// ltcAlbedo.y) (ltcAlbedo.xy: the lobe's albedo split for Schlick's Fresnel; 0 for other lights).
// Its diffuse lobe sees the exact (horizon-clipped) illuminance from the mean direction Ld of the
// light's visible part; for a sphere, a disk or a rect, ltcAlbedo.z > 0 holds the Disney diffuse term
// (without 1/π) averaged over that part (lib/ltc.glsl's rgHorizonDisney), which the standard
// lighting then uses instead of the term at Ld. Ls, specularIlluminance and
// specularNormalisation stay Frostbite's, for lobes other than the standard one (a clear coat).
struct RgLightSample {
    vec3 Ld;
    vec3 diffuseIlluminance;
    vec3 Ls;
    vec3 specularIlluminance;
    float specularNormalisation;
    vec3 specularLtc;
    vec3 ltcAlbedo;
};

int rgLightType(RgLight light) { return int(light.positionType.w + 0.5); }

// P: world position (m), N: unit normal, V: unit direction to the viewer, linearRoughness of the
// specular lobe (1 − smoothness; its α = max(linearRoughness², 1e-3) as rgStandardBrdf's).
// Which of light types `types` (bits 1 << RG_LIGHT_*) the scene has: rgEvaluateLightUnshadowedOf
// compiles only those branches (`types` is a constant at every call). Every light a caller passes
// must be of a type in `types`: a branch whose types are the only ones left takes the light
// without testing its type.
#define RG_LIGHT_IN(types, t) (RG_SCENE_HAS_LIGHT(t) && ((types) & (1u << uint(t))) != 0u)
// Whether every type of `types` the scene has is among `among` (bits): a branch for those needs no
// test of the light's own type (nor the load of it: lavapipe loads a light's fields lane by lane).
#define RG_LIGHT_ONLY(types, among) ((((types) & uint(RG_SCENE_LIGHT_TYPES)) & ~(among)) == 0u)
#define RG_PUNCTUAL_LIGHT_TYPES ((1u << uint(RG_LIGHT_POINT)) | (1u << uint(RG_LIGHT_SPOT)))
#define RG_AREA_LIGHT_TYPES ((1u << uint(RG_LIGHT_SPHERE)) | (1u << uint(RG_LIGHT_DISK)) | (1u << uint(RG_LIGHT_RECT)) | (1u << uint(RG_LIGHT_TUBE)))

RgLightSample rgEvaluateLightUnshadowedOf(RgLight light, uint types, vec3 P, vec3 N, vec3 V, float linearRoughness) {
    int type = rgLightType(light);
    float alpha = max(linearRoughness * linearRoughness, 1e-3);
    vec3 R = rgSpecularDominantDirArea(N, reflect(-V, N), alpha);
    vec3 colour = light.intensity.rgb;
    vec3 dir = light.directionRange.xyz;
    RgLightSample s;
    s.Ld = s.Ls = N;
    s.diffuseIlluminance = s.specularIlluminance = vec3(0.0);
    s.specularNormalisation = 1.0;
    s.specularLtc = vec3(0.0);
    s.ltcAlbedo = vec3(0.0);

    if (RG_LIGHT_IN(types, RG_LIGHT_SUN) && type == RG_LIGHT_SUN) {
        // lst:6: the diffuse part as if the sun were punctual (eq:28), the specular part towards
        // the point of its disk closest to R. params.z, w: sin and cos of the angular radius.
        vec3 D = -dir;
        float r = light.params.z, d = light.params.w;
        float DdotR = dot(D, R);
        vec3 perpendicular = normalize(cross(D, abs(D.y) < 0.99 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0)));
        vec3 S = rgSafeNormalize(R - DdotR * D, perpendicular);
        s.Ld = D;
        s.diffuseIlluminance = colour * clamp(dot(N, D), 0.0, 1.0);
        s.Ls = DdotR < d ? normalize(d * D + S * r) : R;
        s.specularIlluminance = colour;
        // lst:6 has no energy factor ("not found yet"); the sphere's of §4.7.5 with σ keeps a
        // mirror's highlight from exceeding what the disk can give by orders of magnitude.
        float w = rgLobeWidening(alpha, r);
        s.specularNormalisation = w * w;
        return s;
    }

    vec3 Lu = light.positionType.xyz - P;  // to the light's centre
    float sqrDist = max(dot(Lu, Lu), 1e-12);
    float invDist = inversesqrt(sqrDist);
    vec3 L = Lu * invDist;

    if ((RG_LIGHT_IN(types, RG_LIGHT_POINT) || RG_LIGHT_IN(types, RG_LIGHT_SPOT)) && (RG_LIGHT_ONLY(types, RG_PUNCTUAL_LIGHT_TYPES) || type <= RG_LIGHT_SPOT)) {
        // lst:4, eq:27 / lst:5 for an IES profile. A point light's cone (scale 0, offset 1) is 1:
        // where `types` holds no spot light of the scene's it is not evaluated (nor its parameters
        // loaded: the many-lights scene's lighting_standard at 16 384 lights, 1280x720 on
        // lavapipe: ~41 -> ~38 ms).
        float att = getDistanceAtt(Lu, light.directionRange.w);
        if (RG_LIGHT_IN(types, RG_LIGHT_SPOT)) att *= getAngleAtt(-L, dir, light.params.x, light.params.y);
        att *= rgIesAttenuation(light, L);
        vec3 E = colour * att;  // cd / d² = lux
        s.Ld = L;
        s.Ls = L;
        s.diffuseIlluminance = E * clamp(dot(N, L), 0.0, 1.0);
        s.specularIlluminance = E;
        return s;
    }

    vec3 luminance = colour * rgRangeWindow(sqrDist, light.directionRange.w);  // cd/m²
    float radius = light.params.z;
    // LTC: the world → (T1, T2, N) rotation (the diffuse lobe's cosine), the GGX lobe's M⁻¹
    // composed with it, and the lobe's albedo split for Schlick's Fresnel.
    bool ltc = RG_SCENE_HAS_AREA_LIGHT && (types & RG_AREA_LIGHT_TYPES) != 0u && lights.count.y == 1u;  // compiled only for area lights
    mat3 toLocal = mat3(1.0), Minv = mat3(1.0), MinvTable = mat3(1.0);
    if (ltc) {
        toLocal = rgLtcFrame(N, V);
        vec2 albedo;
        rgLtcLookup(linearRoughness, clamp(dot(N, V), 0.0, 1.0), MinvTable, albedo);
        Minv = MinvTable * toLocal;
        s.ltcAlbedo = vec3(albedo, 0.0);
    }

    if (RG_LIGHT_IN(types, RG_LIGHT_SPHERE) && type == RG_LIGHT_SPHERE) {
        // A point inside the sphere: its surface emits outwards, so nothing reaches the point (as in
        // the reference mode) — not the blow-up the formulas below give there.
        if (sqrDist < radius * radius) return s;
        // lst:10, sphere evaluation: clamps keep away from the edge cases and out of the light.
        float sinSigmaSqr = min(radius * radius / sqrDist, 0.9999);
        s.Ld = L;
        s.diffuseIlluminance = luminance * illuminanceSphereOrDisk(clamp(dot(N, L), -0.999, 0.999), sinSigmaSqr);
        // The sphere's point closest to the ray.
        vec3 centreToRay = dot(Lu, R) * R - Lu;
        vec3 closest = Lu + centreToRay * clamp(radius * inversesqrt(max(dot(centreToRay, centreToRay), 1e-20)), 0.0, 1.0);
        s.Ls = rgSafeNormalize(closest, L);
        s.specularIlluminance = luminance * (RG_PI * sinSigmaSqr);
        float w = rgLobeWidening(alpha, radius * invDist);
        s.specularNormalisation = w * w;
        if (ltc) {
            s.ltcAlbedo.z = rgHorizonDisney(L, N, radius * invDist, V, linearRoughness, s.Ld);
            // The disk through the centre that spans the sphere's cone: radius r / cos σ.
            float rho = radius * inversesqrt(1.0 - sinSigmaSqr);
            vec3 T = normalize(cross(L, abs(L.y) < 0.99 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0))) * rho, B = cross(L, T), unused;
            float unusedSin;
            vec3 mean;
            vec3 cL = toLocal * Lu, TL = toLocal * T, BL = toLocal * B;
            s.specularLtc = luminance * (rgLtcCrossesHorizon(cL, TL, BL) ? rgLtcEllipseHorizon(cL, TL, BL, MinvTable, mean)
                                                                          : rgLtcEllipse(Minv * Lu, Minv * T, Minv * B, mean, unusedSin));
            s.specularLtc *= rgLtcSphereRatio(Minv, N, V, alpha, s.ltcAlbedo.x + s.ltcAlbedo.y, L, sinSigmaSqr);
        }
    } else if (RG_LIGHT_IN(types, RG_LIGHT_DISK) && type == RG_LIGHT_DISK) {
        // lst:10, disk evaluation, times the disk's own orientation. It emits along `dir`; its cone
        // (lst:9) attenuates the illuminance.
        float cosLight = clamp(dot(dir, -L), 0.0, 1.0) * rgDiskCone(light, P);
        float sqrRadius = radius * radius;
        float sinSigmaSqr = sqrRadius / (sqrRadius + max(sqrRadius, sqrDist));
        s.Ld = L;
        s.diffuseIlluminance = luminance * (illuminanceSphereOrDisk(dot(N, L), sinSigmaSqr) * cosLight);
        // Where the ray meets the disk's plane, brought inside its rim.
        vec3 offset = rgRayOnPlane(Lu, dir, R) - Lu;
        vec3 closest = Lu + offset * min(1.0, radius * inversesqrt(max(dot(offset, offset), 1e-20)));
        s.Ls = rgSafeNormalize(closest, L);
        s.specularIlluminance = luminance * (RG_PI * sinSigmaSqr * cosLight);
        float w = rgLobeWidening(alpha, radius * invDist);
        s.specularNormalisation = w * w;
        if (ltc) {
            // The disk itself (one-sided), through the cosine (diffuse) and through the lobe's M⁻¹.
            s.diffuseIlluminance = vec3(0.0);
            if (dot(-Lu, dir) > 0.0) {
                float cone = rgDiskCone(light, P);
                vec3 T = normalize(cross(dir, abs(dir.y) < 0.99 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0))) * radius;
                vec3 B = cross(dir, T), axis, lobeMean;
                float sinSq, unusedSin;
                vec3 cL = toLocal * Lu, TL = toLocal * T, BL = toLocal * B;
                bool crosses = rgLtcCrossesHorizon(cL, TL, BL);
                float formFactor = rgLtcEllipse(cL, TL, BL, axis, sinSq);
                axis = axis * toLocal;  // back to world: toLocal is a rotation
                s.ltcAlbedo.z = rgHorizonDisney(axis, N, sqrt(sinSq), V, linearRoughness, s.Ld);
                if (crosses) formFactor = rgLtcEllipseHorizon(cL, TL, BL, mat3(1.0), lobeMean);  // exact clipping
                s.diffuseIlluminance = luminance * (RG_PI * cone * formFactor);
                s.specularLtc = luminance * (cone * (crosses ? rgLtcEllipseHorizon(cL, TL, BL, MinvTable, lobeMean)
                                                             : rgLtcEllipse(Minv * Lu, Minv * T, Minv * B, lobeMean, unusedSin)));
                s.specularLtc *= rgLtcRatio(Minv, N, V, alpha, s.ltcAlbedo.x + s.ltcAlbedo.y, lobeMean);
            }
        }
    } else if (RG_LIGHT_IN(types, RG_LIGHT_RECT) && type == RG_LIGHT_RECT) {
        // seed 002 §4.7.2.5: one-sided, it emits along `dir`; axis: its height direction.
        s.Ld = L;
        s.Ls = L;
        s.diffuseIlluminance = vec3(0.0);
        s.specularIlluminance = vec3(0.0);
        if (dot(-Lu, dir) > 0.0) {
            vec3 up = light.axis.xyz, left = cross(up, dir);
            float halfWidth = 0.5 * light.params.w, halfHeight = 0.5 * light.axis.w;
            vec3 p0 = Lu - left * halfWidth + up * halfHeight;
            vec3 p1 = Lu - left * halfWidth - up * halfHeight;
            vec3 p2 = Lu + left * halfWidth - up * halfHeight;
            vec3 p3 = Lu + left * halfWidth + up * halfHeight;
            float solidAngle = rgRectangleSolidAngle(p0, p1, p2, p3);
            s.diffuseIlluminance = luminance * rgStructuredQuadIlluminance(N, solidAngle, Lu, p0, p1, p2, p3);
            // Where the ray meets the plane, clamped to the rectangle.
            vec3 offset = rgRayOnPlane(Lu, dir, R) - Lu;
            vec3 closest = Lu + left * clamp(dot(offset, left), -halfWidth, halfWidth) +
                           up * clamp(dot(offset, up), -halfHeight, halfHeight);
            s.Ls = rgSafeNormalize(closest, L);
            s.specularIlluminance = luminance * solidAngle;
            s.specularNormalisation = rgLobeWidening(alpha, halfWidth * invDist) * rgLobeWidening(alpha, halfHeight * invDist);
            if (ltc) {
                vec3 towards, unused;
                s.diffuseIlluminance = luminance * (RG_PI * rgLtcQuad(toLocal * p0, toLocal * p1, toLocal * p2, toLocal * p3, towards));
                s.Ld = rgSafeNormalize(towards * toLocal, L);
                // The Disney term averaged over its part above the horizon, by the equivalent sphere.
                vec3 F = rgLtcQuadVector(p0, p1, p2, p3);
                float sinSq = length(F);
                vec3 meanDirection;  // the clipped polygon's mean direction (Ld) is exact already
                if (sinSq > 0.0) s.ltcAlbedo.z = rgHorizonDisney(F / sinSq, N, sqrt(min(sinSq, 0.9999)), V, linearRoughness, meanDirection);
                vec3 lobeMean;
                s.specularLtc = luminance * rgLtcQuadHorizon(toLocal * p0, toLocal * p1, toLocal * p2, toLocal * p3, MinvTable, lobeMean);
                s.specularLtc *= rgLtcRatio(Minv, N, V, alpha, s.ltcAlbedo.x + s.ltcAlbedo.y, lobeMean);
            }
        }
    } else if (RG_LIGHT_IN(types, RG_LIGHT_TUBE)) {  // RG_LIGHT_TUBE
        // seed 002 §4.7.2.6: the capsule as a rectangle (length × 2r) facing the point plus its two
        // half-spheres as one sphere at the segment's closest point. dir: along the tube.
        float lightWidth = light.params.w;
        vec3 L0 = Lu - dir * (0.5 * lightWidth), L1 = Lu + dir * (0.5 * lightWidth);
        vec3 ab = L1 - L0;
        float t = dot(-L0, ab) / max(dot(ab, ab), 1e-20);
        vec3 closestOnLine = L0 + t * ab;
        vec3 closestOnSegment = L0 + clamp(t, 0.0, 1.0) * ab;
        // Inside the capsule: nothing reaches the point (it emits outwards), as for the sphere.
        if (dot(closestOnSegment, closestOnSegment) < radius * radius) return s;
        vec3 forward = rgSafeNormalize(closestOnLine, normalize(cross(dir, abs(dir.y) < 0.99 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0))));
        vec3 up = cross(dir, forward);
        vec3 p0 = Lu - dir * (0.5 * lightWidth) + radius * up;
        vec3 p1 = Lu - dir * (0.5 * lightWidth) - radius * up;
        vec3 p2 = Lu + dir * (0.5 * lightWidth) - radius * up;
        vec3 p3 = Lu + dir * (0.5 * lightWidth) + radius * up;
        float solidAngle = rgRectangleSolidAngle(p0, p1, p2, p3);
        float sqrSphereDistance = max(dot(closestOnSegment, closestOnSegment), 1e-12);
        vec3 sphereL = closestOnSegment * inversesqrt(sqrSphereDistance);
        float sphereFactor = radius * radius / sqrSphereDistance;
        s.Ld = sphereL;
        s.diffuseIlluminance = luminance * (rgStructuredQuadIlluminance(N, solidAngle, Lu, p0, p1, p2, p3) +
                                            RG_PI * clamp(dot(sphereL, N), 0.0, 1.0) * sphereFactor);
        // Karis: the segment's point closest to the ray, then the sphere of radius r around it.
        float RdotL0 = dot(R, L0), RdotAb = dot(R, ab), L0dotAb = dot(L0, ab);
        float tr = (RdotL0 * RdotAb - L0dotAb) / max(dot(ab, ab) - RdotAb * RdotAb, 1e-12);
        vec3 onSegment = L0 + ab * clamp(tr, 0.0, 1.0);
        vec3 centreToRay = dot(onSegment, R) * R - onSegment;
        vec3 closest = onSegment + centreToRay * clamp(radius * inversesqrt(max(dot(centreToRay, centreToRay), 1e-20)), 0.0, 1.0);
        s.Ls = rgSafeNormalize(closest, sphereL);
        s.specularIlluminance = luminance * (solidAngle + RG_PI * min(sphereFactor, 1.0));
        float w = rgLobeWidening(alpha, radius * invDist);
        s.specularNormalisation = w * w * rgLobeWidening(alpha, lightWidth * invDist);  // sphere × line
        if (ltc) {
            // The capsule's outline seen from the point: the cylinder's as a rectangle along the
            // segment, as wide as the tangent planes from the point (r / cos of their half-angle),
            // and each end's half-sphere by the disk that spans its sphere's cone, less what of it
            // the rectangle covers (all of it seen from beyond the end, along the axis).
            float sqrLineDistance = max(dot(closestOnLine, closestOnLine), radius * radius * 1.0001);
            vec3 side = up * (radius * inversesqrt(1.0 - radius * radius / sqrLineDistance));
            vec3 q0 = L0 + side, q1 = L0 - side, q2 = L1 - side, q3 = L1 + side;
            vec3 towards, unused;
            float quadD = rgLtcQuad(toLocal * q0, toLocal * q1, toLocal * q2, toLocal * q3, towards);
            vec3 quadMean;
            float quadS = rgLtcQuadHorizon(toLocal * q0, toLocal * q1, toLocal * q2, toLocal * q3, MinvTable, quadMean);
            float capD = 0.0, capS = 0.0;
            vec3 capTowards = vec3(0.0);
            for (int end = 0; end < 2; ++end) {
                vec3 c = end == 0 ? L0 : L1, other = end == 0 ? L1 : L0;
                float sqrEnd = max(dot(c, c), radius * radius * 1.0001);
                float rho = radius * inversesqrt(1.0 - radius * radius / sqrEnd);
                vec3 toC = c * inversesqrt(sqrEnd);
                // In the plane of the end's disk (through c, facing the point): the rectangle's
                // direction from c (the other end seen through that plane) and its length there.
                float otherDepth = dot(other, toC);
                vec3 inward = otherDepth > 1e-6 ? other * (dot(c, toC) / otherDepth) - c : -c;
                inward -= toC * dot(inward, toC);
                float len = length(inward);
                vec3 T = normalize(cross(toC, abs(toC.y) < 0.99 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0)));
                vec3 outward = len > 1e-9 ? -inward / len : T;
                vec3 across = cross(toC, outward);
                // The disk's outer half as a half-octagon of the same area (two quads), plus the
                // share of its inner half the rectangle does not cover: the strip of depth len,
                // t = len / ρ, covers (t √(1 − t²) + asin t) / π of the disk (½ for t ≥ 1).
                float t = min(len / rho, 1.0);
                float uncovered = 0.5 - (t * sqrt(1.0 - t * t) + asin(t)) / RG_PI;
                float R = rho * 1.05390;  // √(π / (2√2)): the half-octagon's area is the half-disk's
                vec3 p90 = c + across * R, p45 = c + (across + outward) * (0.70710678 * R), p0 = c + outward * R;
                vec3 m45 = c + (outward - across) * (0.70710678 * R), m90 = c - across * R;
                vec3 Tr = T * rho, Br = cross(toC, Tr), e;
                float unusedSin;
                float fullD = rgLtcEllipse(toLocal * c, toLocal * Tr, toLocal * Br, e, unusedSin);
                float halfD = rgLtcQuad(toLocal * c, toLocal * m90, toLocal * m45, toLocal * p0, unused) +
                              rgLtcQuad(toLocal * c, toLocal * p0, toLocal * p45, toLocal * p90, unused);
                float d = halfD + uncovered * fullD;
                capD += d;
                capTowards += e * d;
                capS += rgLtcQuad(Minv * c, Minv * m90, Minv * m45, Minv * p0, unused) +
                        rgLtcQuad(Minv * c, Minv * p0, Minv * p45, Minv * p90, unused) +
                        uncovered * rgLtcEllipse(Minv * c, Minv * Tr, Minv * Br, unused, unusedSin);
            }
            s.diffuseIlluminance = luminance * (RG_PI * (quadD + capD));
            s.Ld = rgSafeNormalize((rgSafeNormalize(towards, vec3(0.0)) * quadD + capTowards) * toLocal, sphereL);
            s.specularLtc = luminance * (quadS + capS);
            s.specularLtc *= rgLtcRatio(Minv, N, V, alpha, s.ltcAlbedo.x + s.ltcAlbedo.y, quadMean);
        }
    }
    return s;
}

// ---- The standard material lit by one light ----------------------------------------------------

// rgStandardBrdf's two halves, so that each lobe can look at the light from its own direction.
// Light i as rgEvaluateLightUnshadowed gives it, times its shadow (lib/shadows.glsl: the sun's
// cascades when the pass is built with RG_SHADOWS, scripts/shadows.lua's `shadows.lit`).
// `sunVisibility`: rgSunVisibility(P, N), taken once per shaded point before the light loop —
// the filtered shadow lookup is the loop's most expensive part, and every light would pay for it.

// Light i whatever its type (every type the scene has).
RgLightSample rgEvaluateLightUnshadowed(uint i, vec3 P, vec3 N, vec3 V, float linearRoughness) {
    return rgEvaluateLightUnshadowedOf(rgLight(i), uint(RG_SCENE_LIGHT_TYPES), P, N, V, linearRoughness);
}

// Light i, its data `light` (rgLight(i), or rgGlobalLight(i)).
RgLightSample rgEvaluateLightOf(RgLight light, uint i, uint types, vec3 P, vec3 N, vec3 V, float linearRoughness, float sunVisibility) {
    RgLightSample s = rgEvaluateLightUnshadowedOf(light, types, P, N, V, linearRoughness);
#ifdef RG_SHADOWS
    float visibility = rgShadow(i, sunVisibility) * rgLocalShadow(i, P, N);
    s.diffuseIlluminance *= visibility;
    s.specularIlluminance *= visibility;
    s.specularLtc *= visibility;  // the LTC lobe of an area light (seed 002 §4.10.4: every specular term is shadowed)
#endif
    return s;
}
RgLightSample rgEvaluateLightOf(uint i, uint types, vec3 P, vec3 N, vec3 V, float linearRoughness, float sunVisibility) {
    return rgEvaluateLightOf(rgLight(i), i, types, P, N, V, linearRoughness, sunVisibility);
}
RgLightSample rgEvaluateLight(uint i, vec3 P, vec3 N, vec3 V, float linearRoughness, float sunVisibility) {
    return rgEvaluateLightOf(i, uint(RG_SCENE_LIGHT_TYPES), P, N, V, linearRoughness, sunVisibility);
}
// The same, looking the sun's shadow up itself (for one light, or where speed does not matter).
RgLightSample rgEvaluateLight(uint i, vec3 P, vec3 N, vec3 V, float linearRoughness) {
    return rgEvaluateLight(i, P, N, V, linearRoughness, rgSunVisibility(P, N));
}

// The diffuse half without ⟨n·l⟩ (the diffuse illuminance carries it): Fr_DisneyDiffuse / π.
float rgDiffuseBrdf(vec3 N, vec3 V, vec3 L, float linearRoughness) {
    float NdotV = abs(dot(N, V)) + 1e-5;  // lst:2
    vec3 H = rgSafeNormalize(V + L, N);
    float LdotH = clamp(dot(L, H), 0.0, 1.0);
    float NdotL = clamp(dot(N, L), 0.0, 1.0);
    return Fr_DisneyDiffuse(NdotV, NdotL, LdotH, linearRoughness) / RG_PI;
}
// The specular half with its ⟨n·l⟩: D · F · Vis / π · ⟨n·l⟩ (f90 and α as in rgStandardBrdf).
vec3 rgSpecularBrdf(vec3 N, vec3 V, vec3 L, vec3 f0, float linearRoughness) {
    float NdotV = abs(dot(N, V)) + 1e-5;
    vec3 H = rgSafeNormalize(V + L, N);
    float LdotH = clamp(dot(L, H), 0.0, 1.0);
    float NdotH = clamp(dot(N, H), 0.0, 1.0);
    float NdotL = clamp(dot(N, L), 0.0, 1.0);
    float alpha = max(linearRoughness * linearRoughness, 1e-3);
    float f90 = rgF90(f0);
    vec3 F = F_Schlick(f0, f90, LdotH);
    return D_GGX(NdotH, alpha) * F * V_SmithGGXCorrelated(NdotL, NdotV, alpha) / RG_PI * NdotL;
}

// Luminance (cd/m²) the standard material reflects from one evaluated light. For a punctual light
// (Ld = Ls, diffuse = specular illuminance × ⟨n·l⟩) it is rgStandardBrdf × the illuminance.
// An area light under the LTC model: its integrated lobe, with Schlick's F(f0, f90) integrated.
vec3 rgStandardLighting(RgLightSample s, vec3 N, vec3 V, vec3 diffuseColor, vec3 f0, float linearRoughness) {
    float diffuse = s.ltcAlbedo.z > 0.0 ? s.ltcAlbedo.z / RG_PI : rgDiffuseBrdf(N, V, s.Ld, linearRoughness);
    vec3 specular;
    if (s.ltcAlbedo.x + s.ltcAlbedo.y > 0.0) {
        float f90 = rgF90(f0);
        specular = s.specularLtc * (f0 * s.ltcAlbedo.x + f90 * s.ltcAlbedo.y);
    } else {
        specular = rgSpecularBrdf(N, V, s.Ls, f0, linearRoughness) * s.specularIlluminance * s.specularNormalisation;
    }
    return diffuseColor * diffuse * s.diffuseIlluminance + specular;
}

uint rgLightCount() { return lights.count.x; }

// The simple interface (generated forward shader): the illuminance (lux) light i delivers at
// `position` on a surface facing it, and the unit direction L towards it — exact for point, spot
// and sun; for an area light, its diffuse illuminance on a surface facing its centre (a tube: the
// closest point of its axis) without the horizon, towards that point.
vec3 rgLightIlluminance(uint i, vec3 position, out vec3 L) {
    RgLight light = rgLight(i);
    int type = rgLightType(light);
    vec3 towards = light.positionType.xyz - position;
    if (type == RG_LIGHT_SUN) towards = -light.directionRange.xyz;
    if (type == RG_LIGHT_TUBE) {  // the closest point of the segment p0 p1 (relative to position)
        vec3 ab = light.directionRange.xyz * light.params.w;
        vec3 p0 = towards - 0.5 * ab;
        towards = p0 + clamp(dot(-p0, ab) / max(dot(ab, ab), 1e-20), 0.0, 1.0) * ab;
    }
    L = rgSafeNormalize(towards, vec3(0.0, 1.0, 0.0));
    return rgEvaluateLight(i, position, L, L, 1.0).diffuseIlluminance;
}

#endif

#version 460
// The in-engine reference mode (seed 000 §2.3: "brute-force sampling of the light integration on
// the GPU" to validate the approximations; §4.7: an in-engine reference that importance-samples
// every area light; seed 002 §4.7: the area-light integral
//   L_out = ∫_Ω f(v, l) L_in ⟨n·l⟩ dl = ∫_A f(v, l) L_in ⟨n·l⟩ ⟨n_a·−l⟩ / d² dA,
// which has no closed form in general but can be integrated by Monte Carlo and importance
// sampling). Direct lighting only — unoccluded like the real-time approximations
// (shaders/lib/lighting.glsl), or with Params.reference_shadows every light sample, every BRDF
// sample that meets a light and every environment sample casts a shadow ray through the scene's
// opaque triangles (lib/bvh.glsl: the same geometry the G-buffer and the shadow maps draw, no
// alpha test) — of the standard material with exactly rgStandardBrdf's BRDF:
// renormalised Disney diffuse (lst:1) + GGX / height-correlated Smith / Schlick with f90 (lst:2),
// so `rgraph compare` against deferred.lua measures only the light approximations.
//
//   point, spot   delta lights: evaluated exactly, lst:4 (windowed inverse square, cone) and
//                 eq:27 / lst:5 (IES) — the formula of rgEvaluateLight's punctual branch.
//   sun           a disk of angular radius σ (params.z = sin σ), uniform radiance
//                 E⊥ / (2π (1 − cos σ)) over its cone; sampled uniformly in the cone.
//   sphere        luminance × the range window; the cone it subtends sampled uniformly by solid
//                 angle. Below the horizon a sample simply gets ⟨n·l⟩ = 0: the exact horizon
//                 handling lst:10 approximates (seed 000 §4.7.2.2–4; seed 002 §4.7.2.2–4).
//                 Like every emitter here it emits outwards only: a point inside a sphere or a
//                 tube gets nothing from it (lighting.glsl clamps the sphere to sin²σ = 0.9999).
//   disk, rect    one-sided emitters along directionRange.xyz; uniform area sampling,
//                 pdf_ω = pdf_A · d² / ⟨n_a·−l⟩ (seed 002 §4.7: the area form of the integral).
//   tube          a capsule (cylinder of length params.w and radius params.z along
//                 directionRange.xyz, plus two hemispherical caps), area sampling of its surface
//                 (the cylinder's half facing the point by projected width, the caps uniformly:
//                 see TubeSampling); samples on the side turned away contribute 0 (convex emitter).
// Every sampled light also receives the pixel's BRDF sample (diffuse cosine lobe, GGX visible
// normals, or the coat's), intersected analytically with its shape (ray–cone for sun and sphere,
// ray–disk, ray–rectangle, ray–capsule); the light's sample and the BRDF's are combined with the
// power heuristic (Veach, β = 2). Area lights keep lighting.glsl's rgRangeWindow of the squared
// distance to the light's centre (lst:4's window), so the two stay comparable.
// The environment (the scene's SceneEnvironment, lib/environment.glsl — the distant probe the
// real-time path pre-filters, scripts/ibl.lua) is one more sampled light: each sample draws a
// direction from its luminance distribution (SceneEnvironmentCdf: graph/scene/environment.h's
// EnvironmentCdf, cells by (dilated) mean luminance × sin θ, marginal then conditional CDF) and the BRDF's
// sample reads the radiance where it points, the two combined with the power heuristic as for
// the lights — so a small bright source in an HDRI converges as fast as a sky. Unoccluded like
// the split sum it checks, unless reference_shadows.
// Clear coat (RG_MATERIAL_IDENTITY_clear_coat, materials/clearcoat.lua) gets its coat lobe too, about
// the coat's own normal, evaluated per direction as materials/clearcoat_shading.glsl does for one
// light direction. The two-colour
// material (materials/two_colour.lua) is unpacked with its own layout into the same diffuse colour
// and f0. The sheen material (RG_MATERIAL_IDENTITY_sheen, materials/sheen.lua) adds its Charlie lobe
// per direction and scales the base by 1 − max(sheen colour) · E (E from the DFG table's w, as
// materials/sheen_shading.glsl); its broad lobe is sampled by the cosine lobe.
//
// Progressive: each frame adds Params.reference_samples samples to the running mean in the
// persistent `reference_accum` (rgb: absolute cd/m²; a: how many frames it holds — the target
// starts as zeros, and again whenever the session resets its history), then writes it
// pre-exposed to `hdr`. Random numbers: shaders/lib/sampling.glsl's PCG stream, seeded by the
// PCG hash of (pixel x, pixel y, frames accumulated, Params.reference_seed); samples draw
// consecutively from it.
#include "lib/lighting.glsl"
#include "lib/exposure.glsl"
#include "lib/sampling.glsl"
#include "lib/environment.glsl"
#include "lib/bvh.glsl"
#include "gbuffer_pipeline.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 0) uniform sampler2D GB0;
layout(set = 0, binding = 1) uniform sampler2D GB1;
layout(set = 0, binding = 2) uniform sampler2D GB2;
layout(set = 0, binding = 3) uniform sampler2D GB3;
layout(set = 0, binding = 4) uniform sampler2D depth;
layout(set = 0, binding = 11) uniform usampler2D depth_stencil;  // the material identity
layout(set = 0, binding = 5, std430) readonly buffer exposure { RgExposureState state; } ex;
layout(set = 0, binding = 6, rgba16f) uniform writeonly image2D hdr;
layout(set = 0, binding = 7, rgba32f) uniform image2D reference_accum;
layout(set = 0, binding = 8) uniform Params {
    float reference_samples;  // samples per pixel per frame
    float reference_seed;
    float reference_strategy;  // 0 MIS, 1 light sampling only, 2 BRDF sampling only
    float reference_shadows;   // 1: every light and environment sample casts a shadow ray
    float initial_ev100;
} params;
layout(set = 0, binding = 9) uniform sampler2D SceneEnvironment;  // the scene's (1x1 black without one)
layout(set = 0, binding = 26) uniform sampler2D dfg;  // scripts/ibl.lua's table: w the sheen lobe's albedo
layout(set = 0, binding = 10, std430) readonly buffer SceneEnvironmentCdf {
    uvec4 size;    // columns, rows
    float data[];  // rows + 1 marginal CDF values, rows × (columns + 1) conditional ones, rows × columns cell probabilities
} rgEnvCdf;

// The last i in [0, n) with data[base + i] <= u (the values ascend from 0).
uint envFindInterval(uint base, uint n, float u) {
    uint lo = 0u, hi = n;
    while (hi - lo > 1u) {
        uint mid = (lo + hi) / 2u;
        if (rgEnvCdf.data[base + mid] <= u) lo = mid;
        else hi = mid;
    }
    return lo;
}
// The environment's sampling density (solid angle) in direction d: the cell's probability ×
// columns × rows over the unit square, / (2π² sin θ) on the sphere (EnvironmentCdf::pdf).
float envPdf(vec3 d) {
    uint w = rgEnvCdf.size.x, h = rgEnvCdf.size.y;
    // rgEquirectUv's v through atan rather than acos: precise near the poles and at cell edges.
    vec2 uv = vec2(rgEquirectUv(d).x, atan(length(d.xz), d.y) / RG_PI);
    float sinTheta = sin(clamp(uv.y, 0.0, 1.0) * RG_PI);
    if (sinTheta <= 0.0) return 0.0;
    uint c = min(w - 1u, uint(fract(uv.x) * float(w))), r = min(h - 1u, uint(clamp(uv.y, 0.0, 1.0) * float(h)));
    return rgEnvCdf.data[h + 1u + h * (w + 1u) + r * w + c] * float(w * h) / (2.0 * RG_PI * RG_PI * sinTheta);
}
// A direction drawn from the distribution with two uniform numbers (EnvironmentCdf::sample).
float sampleEnvironment(vec2 u, out vec3 L) {
    uint w = rgEnvCdf.size.x, h = rgEnvCdf.size.y;
    uint r = envFindInterval(0u, h, u.y);
    float r0 = rgEnvCdf.data[r], r1 = rgEnvCdf.data[r + 1u];
    float fy = r1 > r0 ? clamp((u.y - r0) / (r1 - r0), 0.0, 1.0) : 0.5;
    uint row = h + 1u + r * (w + 1u);
    uint c = envFindInterval(row, w, u.x);
    float c0 = rgEnvCdf.data[row + c], c1 = rgEnvCdf.data[row + c + 1u];
    float fx = c1 > c0 ? clamp((u.x - c0) / (c1 - c0), 0.0, 1.0) : 0.5;
    vec2 uv = vec2((float(c) + fx) / float(w), (float(r) + fy) / float(h));
    L = rgEquirectDirection(uv);
    // The density of the cell drawn, not envPdf(L): mapping L back through acos can land a sample
    // near a cell's edge in its neighbour, and a bright cell's sample weighted by a dim
    // neighbour's density is a firefly (measured: a 20 000-nit patch read 4.7x too bright).
    float sinTheta = sin(uv.y * RG_PI);
    if (sinTheta <= 0.0) return 0.0;
    return rgEnvCdf.data[h + 1u + h * (w + 1u) + r * w + c] * float(w * h) / (2.0 * RG_PI * RG_PI * sinTheta);
}

// ---- The shaded point and its BRDF --------------------------------------------------------------

struct Shading {
    vec3 P, N, V;
    vec3 diffuseColor, f0;
    float f90, linearRoughness, alpha;
    float NdotV;      // lst:2's |N·V| + 1e-5, as the real-time BRDF
    vec3 Vs;          // V lifted above the horizon for sampling the GGX visible normals
    float NdotVs;
    vec3 T, B;        // tangent frame around N
    bool coat;        // RG_MATERIAL_IDENTITY_clear_coat (materials/clearcoat.lua): a second GGX lobe on top
    float coatStrength, coatAlpha;
    vec3 coatN, coatT, coatB;  // the coat's own normal (the vertex normal or its normal map) and frame
    vec3 coatVs;               // V lifted above the coat's horizon, as Vs
    float coatNdotV, coatNdotVs;
    vec3 sheenColor;       // RG_MATERIAL_IDENTITY_sheen (materials/sheen.lua): 0 for every other material
    float sheenAlpha, sheenScaling;  // the Charlie lobe's α; 1 − max(sheen colour) · E(N·V)
    vec3 lobeProbability;  // of picking the diffuse, GGX and coat lobes for the BRDF sample
};

// A layer's view terms about its normal N: lst:2's |N·V| + 1e-5, and for sampling V above the
// surface — where N faces away from the camera, the (arbitrary but consistent) sampling view is V
// raised to a grazing 1e-3 above the horizon — with its N·V and the tangent frame around N.
void viewTerms(vec3 N, vec3 V, out float NdotV, out vec3 Vs, out float NdotVs, out vec3 T, out vec3 B) {
    NdotV = abs(dot(N, V)) + 1e-5;
    float rawNdotV = dot(N, V);
    Vs = rawNdotV > 1e-3 ? V : normalize(V + (1e-3 - rawNdotV) * N);
    NdotVs = max(dot(N, Vs), 1e-3);
    rgBasis(N, T, B);
}

// rgStandardBrdf: (diffuse · Fr_DisneyDiffuse / π + D · F · Vis / π) · ⟨n·l⟩, term for term. With a
// coat (materials/clearcoat_shading.glsl, per direction, about the coat's normal): base · (1 − Fc) + D_c · Vis_c · Fc / π · ⟨n·l⟩,
// Fc = F_Schlick(0.04, 1, ⟨l·h⟩) · coatStrength.
// Each layer sees L above its own normal's horizon: a coat over a normal-mapped base reflects
// directions the base's normal turns away from.
vec3 brdfCos(Shading s, vec3 L) {
    vec3 base = vec3(0.0);
    float NdotL = dot(s.N, L);
    if (NdotL > 0.0) {
        vec3 H = rgSafeNormalize(s.V + L, s.N);
        float LdotH = clamp(dot(L, H), 0.0, 1.0);
        float NdotH = clamp(dot(s.N, H), 0.0, 1.0);
        NdotL = min(NdotL, 1.0);
        vec3 F = F_Schlick(s.f0, s.f90, LdotH);
        float Vis = V_SmithGGXCorrelated(NdotL, s.NdotV, s.alpha);
        float D = D_GGX(NdotH, s.alpha);
        float Fd = Fr_DisneyDiffuse(s.NdotV, NdotL, LdotH, s.linearRoughness) / RG_PI;
        base = (s.diffuseColor * Fd + D * F * Vis / RG_PI) * NdotL;
        base = base * s.sheenScaling + rgSheenBrdf(s.sheenColor, NdotH, NdotL, s.NdotV, s.sheenAlpha) * NdotL;
    }
    if (!s.coat) return base;
    // The coat about its own normal (materials/clearcoat_shading.glsl).
    float coatNdotL = clamp(dot(s.coatN, L), 0.0, 1.0);
    vec3 Hc = rgSafeNormalize(s.V + L, s.coatN);
    float Fc = F_Schlick(0.04, 1.0, clamp(dot(L, Hc), 0.0, 1.0)) * s.coatStrength;
    float coat = D_GGX(clamp(dot(s.coatN, Hc), 0.0, 1.0), s.coatAlpha) *
                 V_SmithGGXCorrelated(coatNdotL, s.coatNdotV, s.coatAlpha) * Fc / RG_PI * coatNdotL;
    return base * (1.0 - Fc) + vec3(coat);
}

// pdf (solid angle) of the BRDF sampling strategy: the mixture of the cosine lobe and the GGX
// visible-normal reflections of the base (and of the coat).
// With a coat, every lobe's density counts wherever the BRDF is not zero: the base's GGX
// reflections below the base's horizon too, where the coat still reflects.
float brdfPdf(Shading s, vec3 L) {
    float NdotL = dot(s.N, L);
    if (NdotL <= 0.0 && !s.coat) return 0.0;
    vec3 H = rgSafeNormalize(s.Vs + L, s.N);
    float NdotH = dot(s.N, H), VdotH = dot(s.Vs, H);
    float pdf = s.lobeProbability.x * max(NdotL, 0.0) / RG_PI;
    if (NdotH > 0.0) pdf += s.lobeProbability.y * rgGgxVisibleReflectionPdf(s.NdotVs, NdotH, VdotH, s.alpha);
    if (s.lobeProbability.z > 0.0 && dot(s.coatN, L) > 0.0) {
        vec3 Hc = rgSafeNormalize(s.coatVs + L, s.coatN);
        float NcdotH = dot(s.coatN, Hc);
        if (NcdotH > 0.0)
            pdf += s.lobeProbability.z * rgGgxVisibleReflectionPdf(s.coatNdotVs, NcdotH, dot(s.coatVs, Hc), s.coatAlpha);
    }
    return pdf;
}

// Draws the BRDF sample; returns its pdf (0: unusable, e.g. below the horizon).
float sampleBrdf(Shading s, inout RgRng rng, out vec3 L) {
    float pick = rgRngNext(rng);
    vec2 u = rgRngNext2(rng);
    if (pick >= s.lobeProbability.x) {
        // The coat lobe only when there is one (rounding could put `pick` past x + y without).
        bool coatLobe = s.lobeProbability.z > 0.0 && pick >= s.lobeProbability.x + s.lobeProbability.y;
        if (coatLobe) {  // about the coat's normal
            vec3 Ve = vec3(dot(s.coatVs, s.coatT), dot(s.coatVs, s.coatB), s.coatNdotVs);
            vec3 H = rgToWorld(rgSampleGgxVisibleNormal(Ve, s.coatAlpha, u), s.coatT, s.coatB, s.coatN);
            L = reflect(-s.coatVs, H);
        } else {
            vec3 Ve = vec3(dot(s.Vs, s.T), dot(s.Vs, s.B), s.NdotVs);
            vec3 H = rgToWorld(rgSampleGgxVisibleNormal(Ve, s.alpha, u), s.T, s.B, s.N);
            L = reflect(-s.Vs, H);
        }
    } else {
        L = rgToWorld(rgSampleCosineHemisphere(u), s.T, s.B, s.N);
    }
    L = normalize(L);
    return brdfPdf(s, L);
}

// ---- Lights: sampling and intersection ----------------------------------------------------------

// The radiance (cd/m²) a sampled light shows, constant over its shape: the sun's E⊥ spread over
// its cone, an area light's luminance times the range window of its centre (as lighting.glsl).
vec3 lightRadiance(RgLight light, int type, vec3 P) {
    if (type == RG_LIGHT_SUN) {
        // A uniform disk of half-angle σ gives a surface facing it ∫ L cos θ dω = L · π sin²σ:
        // L = E⊥ / (π sin²σ) (graph/lighting's sunLuminance), not E⊥ over the solid angle.
        return light.intensity.rgb / (RG_PI * light.params.z * light.params.z);
    }
    vec3 Lu = light.positionType.xyz - P;
    // A disk's cone (lst:9) attenuates what it gives the point, as in the real-time evaluation.
    float cone = type == RG_LIGHT_DISK ? rgDiskCone(light, P) : 1.0;
    return light.intensity.rgb * (rgRangeWindow(max(dot(Lu, Lu), 1e-12), light.directionRange.w) * cone);
}

// Area sampling, as a direction: pdf_ω = pdf_A · d² / ⟨n_a·−l⟩; 0 where the sampled point shows
// its back (one-sided disk and rect, the far side of a capsule).
float areaToSolidAngle(vec3 toPoint, vec3 lightNormal, float pdfArea, out vec3 L) {
    float d2 = dot(toPoint, toPoint);
    L = toPoint * inversesqrt(max(d2, 1e-20));
    float cosLight = dot(lightNormal, -L);
    return cosLight > 0.0 && d2 > 0.0 ? pdfArea * d2 / cosLight : 0.0;
}

// The nearest t > 0 where the ray P + t·D (D unit) enters the sphere (centre c, radius r) from
// outside; −1 when it misses or starts inside.
float raySphere(vec3 P, vec3 D, vec3 c, float r) {
    vec3 oc = P - c;
    float b = dot(oc, D), cc = dot(oc, oc) - r * r;
    if (cc <= 0.0) return -1.0;
    float disc = b * b - cc;
    if (disc < 0.0) return -1.0;
    float t = -b - sqrt(disc);
    return t > 0.0 ? t : -1.0;
}

// Where the ray meets a one-sided emitter's plane (centre c, emitting along n) from its front:
// returns t, −1 when it runs parallel, away or into the back.
float rayFrontPlane(vec3 P, vec3 D, vec3 c, vec3 n) {
    float denom = dot(D, n);
    if (denom >= -1e-7) return -1.0;
    float t = dot(c - P, n) / denom;
    return t > 0.0 ? t : -1.0;
}

// The tube's (capsule's) sampling — by area, not uniformly: the lateral surface is sampled over
// its half facing P (the side the point can see: w, the unit direction from the axis to P, is the
// same along the whole axis) with the point's angle φ from w distributed as x = sin φ uniform —
// uniform in the cylinder's projected width, pdf_A = cos φ / (2 r len), about proportional to
// ⟨n_a·−l⟩ — and the two hemispherical caps uniformly by area (pdf_A = 1 / 4πr²). Uniform area
// sampling of the whole capsule wastes the half turned away and left ~3.7 % noise on the floor of
// tests/gpu/scenes/reference_tube.lua after 1024 samples; this leaves ~1.5 %. The cylinder is
// picked with the share of its projected area
// (2 r len against π r² for the caps), never when P lies within the cylinder's radius of the axis
// (beyond an end, where the lateral surface shows only its back).
struct TubeSampling { vec3 w, v; float cylinderProbability; };
TubeSampling tubeSampling(RgLight light, vec3 P) {
    vec3 dir = light.directionRange.xyz;
    vec3 o = P - light.positionType.xyz;
    vec3 perp = o - dot(o, dir) * dir;
    float rho2 = dot(perp, perp), radius = light.params.z, len = light.params.w;
    TubeSampling ts;
    vec3 t, b;
    rgBasis(dir, t, b);
    ts.w = rho2 > 1e-20 ? perp * inversesqrt(rho2) : t;
    ts.v = cross(dir, ts.w);
    ts.cylinderProbability = rho2 > radius * radius ? 2.0 * len / (2.0 * len + RG_PI * radius) : 0.0;
    return ts;
}

// Draws a direction L towards light `light` from P with the light's strategy; returns its pdf
// (solid angle; 0: the sample contributes nothing). u: three uniform numbers.
float sampleLight(RgLight light, int type, vec3 P, vec3 u, out vec3 L) {
    vec3 dir = light.directionRange.xyz;
    vec3 c = light.positionType.xyz;
    float radius = light.params.z;
    vec3 t, b;
    if (type == RG_LIGHT_SUN) {
        vec3 D = -dir;
        float oneMinusCos = rgOneMinusCosFromSinSqr(light.params.z * light.params.z);
        rgBasis(D, t, b);
        L = normalize(rgToWorld(rgSampleCone(u.xy, oneMinusCos), t, b, D));
        return 1.0 / (2.0 * RG_PI * oneMinusCos);
    }
    vec3 Lu = c - P;
    float d2 = dot(Lu, Lu);
    if (type == RG_LIGHT_SPHERE) {
        if (d2 <= radius * radius) {  // inside: every direction sees the back of the (outward) emitter
            L = vec3(0.0, 1.0, 0.0);
            return 0.0;
        }
        vec3 axis = Lu * inversesqrt(d2);
        float oneMinusCos = rgOneMinusCosFromSinSqr(radius * radius / d2);
        rgBasis(axis, t, b);
        L = normalize(rgToWorld(rgSampleCone(u.xy, oneMinusCos), t, b, axis));
        return 1.0 / (2.0 * RG_PI * oneMinusCos);
    }
    if (type == RG_LIGHT_DISK) {
        rgBasis(dir, t, b);
        float r = radius * sqrt(u.x), phi = 2.0 * RG_PI * u.y;
        vec3 y = c + r * (cos(phi) * t + sin(phi) * b);
        return areaToSolidAngle(y - P, dir, 1.0 / (RG_PI * radius * radius), L);
    }
    if (type == RG_LIGHT_RECT) {
        vec3 up = light.axis.xyz, left = cross(up, dir);
        float halfWidth = 0.5 * light.params.w, halfHeight = 0.5 * light.axis.w;
        vec3 y = c + left * ((2.0 * u.x - 1.0) * halfWidth) + up * ((2.0 * u.y - 1.0) * halfHeight);
        return areaToSolidAngle(y - P, dir, 1.0 / (4.0 * halfWidth * halfHeight), L);
    }
    // RG_LIGHT_TUBE: see TubeSampling.
    TubeSampling ts = tubeSampling(light, P);
    vec3 y, n;
    float pdfArea;
    if (u.z < ts.cylinderProbability) {  // x = sin φ uniform over the half facing P
        float x = 2.0 * u.y - 1.0, cosPhi = sqrt(max(0.0, 1.0 - x * x));
        n = cosPhi * ts.w + x * ts.v;
        y = c + dir * ((u.x - 0.5) * light.params.w) + radius * n;
        pdfArea = ts.cylinderProbability * cosPhi / (2.0 * radius * light.params.w);
    } else {  // a uniform point of the sphere, moved to the end cap of its hemisphere
        n = rgSampleSphere(u.xy);
        y = c + dir * (dot(n, dir) >= 0.0 ? 0.5 : -0.5) * light.params.w + radius * n;
        pdfArea = (1.0 - ts.cylinderProbability) / (4.0 * RG_PI * radius * radius);
    }
    return areaToSolidAngle(y - P, n, pdfArea, L);
}

// Whether the ray from P along D (unit) meets the light's emitting side, and the pdf with which
// sampleLight would have drawn D (for the MIS weight of a BRDF sample).
float lightPdfAlong(RgLight light, int type, vec3 P, vec3 D) {
    vec3 dir = light.directionRange.xyz;
    vec3 c = light.positionType.xyz;
    float radius = light.params.z;
    if (type == RG_LIGHT_SUN) {
        // The cone test by its sine (precise for σ ≈ 0.27°): ⟨D·−dir⟩ > 0 and sin² ≤ sin² σ.
        vec3 x = cross(D, -dir);
        float sinSqr = light.params.z * light.params.z;
        if (dot(D, -dir) <= 0.0 || dot(x, x) > sinSqr) return 0.0;
        return 1.0 / (2.0 * RG_PI * rgOneMinusCosFromSinSqr(sinSqr));
    }
    vec3 Lu = c - P;
    float d2 = dot(Lu, Lu);
    if (type == RG_LIGHT_SPHERE) {
        if (d2 <= radius * radius) return 0.0;  // inside: see sampleLight
        vec3 x = cross(D, Lu);  // |D × Lu|² = d² sin² of the angle to the centre ≤ r²: inside the cone
        if (dot(D, Lu) <= 0.0 || dot(x, x) > radius * radius) return 0.0;
        return 1.0 / (2.0 * RG_PI * rgOneMinusCosFromSinSqr(radius * radius / d2));
    }
    if (type == RG_LIGHT_DISK || type == RG_LIGHT_RECT) {
        float t = rayFrontPlane(P, D, c, dir);
        if (t < 0.0) return 0.0;
        vec3 q = P + t * D - c;
        float pdfArea;
        if (type == RG_LIGHT_DISK) {
            if (dot(q, q) > radius * radius) return 0.0;
            pdfArea = 1.0 / (RG_PI * radius * radius);
        } else {
            vec3 up = light.axis.xyz, left = cross(up, dir);
            float halfWidth = 0.5 * light.params.w, halfHeight = 0.5 * light.axis.w;
            if (abs(dot(q, left)) > halfWidth || abs(dot(q, up)) > halfHeight) return 0.0;
            pdfArea = 1.0 / (4.0 * halfWidth * halfHeight);
        }
        return pdfArea * t * t / -dot(D, dir);
    }
    // RG_LIGHT_TUBE: the nearest entry into the union of the cylinder (lateral surface within the
    // segment) and the two end balls is the capsule's; a flat end of the cylinder lies inside a ball.
    float len = light.params.w;
    vec3 o = P - c;
    vec3 onAxis = dir * clamp(dot(o, dir), -0.5 * len, 0.5 * len);
    if (dot(o - onAxis, o - onAxis) <= radius * radius) return 0.0;  // inside: see sampleLight
    TubeSampling ts = tubeSampling(light, P);
    float best = 1e30, pdfArea = 0.0;
    vec3 normal = vec3(0.0);
    vec3 oPerp = o - dot(o, dir) * dir, dPerp = D - dot(D, dir) * dir;
    float a = dot(dPerp, dPerp), bq = dot(oPerp, dPerp), cq = dot(oPerp, oPerp) - radius * radius;
    if (a > 1e-12 && cq > 0.0) {
        float disc = bq * bq - a * cq;
        if (disc >= 0.0) {
            float t = (-bq - sqrt(disc)) / a;
            if (t > 0.0 && abs(dot(o, dir) + t * dot(D, dir)) <= 0.5 * len) {
                best = t;
                normal = normalize(oPerp + t * dPerp);
                pdfArea = ts.cylinderProbability * max(dot(normal, ts.w), 0.0) / (2.0 * radius * len);
            }
        }
    }
    for (int e = 0; e < 2; ++e) {
        vec3 centre = c + dir * (e == 0 ? 0.5 * len : -0.5 * len);
        float t = raySphere(P, D, centre, radius);
        if (t > 0.0 && t < best) {
            best = t;
            normal = (P + t * D - centre) / radius;
            pdfArea = (1.0 - ts.cylinderProbability) / (4.0 * RG_PI * radius * radius);
        }
    }
    if (best >= 1e30) return 0.0;
    float cosLight = dot(normal, -D);
    return cosLight > 0.0 ? pdfArea * best * best / cosLight : 0.0;
}

// ---- Shadow rays ---------------------------------------------------------------------------------

// How far along L (unit) from P the light's surface is: where a shadow ray towards it ends. The
// sun and the environment: nowhere. A tube: its axis's point nearest P, less the radius (geometry
// inside a light's volume is not meaningful).
float lightDistance(RgLight light, int type, vec3 P, vec3 L) {
    if (type == RG_LIGHT_SUN) return 1e30;
    vec3 c = light.positionType.xyz, dir = light.directionRange.xyz;
    vec3 Lu = c - P;
    if (type <= RG_LIGHT_SPOT) return length(Lu);
    if (type == RG_LIGHT_SPHERE) {
        float t = raySphere(P, L, c, light.params.z);
        return t > 0.0 ? t : length(Lu);
    }
    if (type == RG_LIGHT_DISK || type == RG_LIGHT_RECT) {
        float denom = dot(L, dir);
        return abs(denom) > 1e-7 ? max(dot(c - P, dir) / denom, 0.0) : length(Lu);
    }
    float len = light.params.w;
    vec3 onAxis = c + dir * clamp(dot(P - c, dir), -0.5 * len, 0.5 * len);
    return max(length(onAxis - P) - light.params.z, 0.0);
}

// Whether nothing of the scene lies between P and `distance` along L (Params.reference_shadows;
// always true without). The ray starts 2 mm off the surface, on L's side of it.
bool unoccluded(Shading s, vec3 L, float distance) {
    const float offset = 2e-3;
    vec3 o = s.P + s.N * (dot(s.N, L) >= 0.0 ? offset : -offset) + L * offset;
    return !rgOccluded(o, L, params.reference_shadows > 0.5 ? distance - 2.0 * offset : 0.0);
}

// ---- Punctual lights, exactly -------------------------------------------------------------------

// lst:4 / eq:27 / lst:5: the illuminance of a point or spot light at P, on a surface facing it,
// times the BRDF — rgEvaluateLight's punctual branch with the same helpers.
vec3 punctual(Shading s, RgLight light) {
    vec3 Lu = light.positionType.xyz - s.P;
    float sqrDist = max(dot(Lu, Lu), 1e-12);
    vec3 L = Lu * inversesqrt(sqrDist);
    float att = getDistanceAtt(Lu, light.directionRange.w);
    att *= getAngleAtt(-L, light.directionRange.xyz, light.params.x, light.params.y);
    att *= rgIesAttenuation(light, L);
    return unoccluded(s, L, sqrt(sqrDist)) ? brdfCos(s, L) * light.intensity.rgb * att : vec3(0.0);
}

bool finite3(vec3 v) { return !any(isnan(v)) && !any(isinf(v)); }

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(hdr);
    if (any(greaterThanEqual(p, size))) return;
    vec4 previous = imageLoad(reference_accum, p);
    uint frame = uint(max(previous.a, 0.0) + 0.5);  // frames accumulated so far
    float pre = rgPreExposure(ex.state, params.initial_ev100);

    float z = texelFetch(depth, p, 0).r;
    if (z >= 1.0) {  // the far plane: left to the sky pass
        imageStore(reference_accum, p, vec4(0.0, 0.0, 0.0, float(frame + 1u)));
        imageStore(hdr, p, vec4(0.0, 0.0, 0.0, 1.0));
        return;
    }
    // Each pixel decoded with its own material's layout (gbuffer_pipeline.glsl): the standard
    // parameters it holds, neutral values for those it does not.
    vec4 t0 = texelFetch(GB0, p, 0), t1 = texelFetch(GB1, p, 0), t2 = texelFetch(GB2, p, 0), t3 = texelFetch(GB3, p, 0);
    RgGBufferView g = rgDecodeGBuffer(texelFetch(depth_stencil, p, 0).r, t0, t1, t2, t3);
    if ((g.has & RG_VIEW_SMOOTHNESS) == 0u) g.smoothness = 0.5;
    if ((g.has & RG_VIEW_REFLECTANCE) == 0u) g.reflectance = 0.5;
    Shading s;
    vec2 uv = (vec2(p) + 0.5) / vec2(size);
    s.P = rgWorldPosition(uv, z);
    s.N = g.normal;
    s.V = rgViewDirection(s.P);
    // §3.2.1, as deferred_lighting.frag and rgStandardBrdf; a layout that keeps an f0 colour (the
    // two-colour material) gives its diffuse and f0 colours as stored.
    s.diffuseColor = g.baseColor * (1.0 - g.metalMask);
    s.f0 = mix(vec3(rgDielectricF0(g.reflectance)), g.baseColor, g.metalMask);
    if ((g.has & RG_VIEW_F0) != 0u) {
        s.diffuseColor = g.baseColor;
        s.f0 = g.f0;
    }
    s.f90 = rgF90(s.f0);
    s.linearRoughness = 1.0 - g.smoothness;
    s.alpha = max(s.linearRoughness * s.linearRoughness, 1e-3);
    viewTerms(s.N, s.V, s.NdotV, s.Vs, s.NdotVs, s.T, s.B);
    // The clear coat's own channels (materials/clearcoat.lua's layout): strength, smoothness and
    // normal, with the coat's view terms and sampling frame as the base's above.
    s.coat = false;
    s.coatStrength = 0.0;
    s.coatAlpha = 1.0;
    s.coatN = s.N;
#ifdef RG_MATERIAL_IDENTITY_clear_coat
    if (g.identity == RG_MATERIAL_IDENTITY_clear_coat) {
        GBuffer_clearcoat coat = unpackGBuffer_clearcoat(t0, t1, t2, t3);
        s.coat = true;
        s.coatStrength = coat.coatWeight;
        s.coatAlpha = max((1.0 - coat.coatGloss) * (1.0 - coat.coatGloss), 1e-3);
        s.coatN = coat.coatNormal;
    }
#endif
    viewTerms(s.coatN, s.V, s.coatNdotV, s.coatVs, s.coatNdotVs, s.coatT, s.coatB);
    s.sheenColor = vec3(0.0);
    s.sheenAlpha = 1.0;
    s.sheenScaling = 1.0;
#ifdef RG_MATERIAL_IDENTITY_sheen
    if (g.identity == RG_MATERIAL_IDENTITY_sheen) {
        GBuffer_sheen sheen = unpackGBuffer_sheen(t0, t1, t2, t3);
        s.sheenColor = sheen.sheenColor;
        s.sheenAlpha = rgSheenAlpha(sheen.sheenRoughness);
        vec2 at = clamp(vec2(clamp(dot(s.N, s.V), 1e-4, 1.0), sheen.sheenRoughness), vec2(0.5 / 128.0), vec2(1.0 - 0.5 / 128.0));
        s.sheenScaling = rgSheenScaling(s.sheenColor, textureLod(dfg, at, 0.0).w);
    }
#endif
    // Lobe selection by the lobes' albedo estimates (diffuse colour, Schlick at N·V for the GGX
    // lobes), each present lobe picked with probability at least 0.1 so that none is starved.
    const vec3 luma = vec3(0.2126, 0.7152, 0.0722);
    float Fc = s.coat ? F_Schlick(0.04, 1.0, s.coatNdotV) * s.coatStrength : 0.0;
    vec3 w = vec3(dot(s.diffuseColor, luma) * (1.0 - Fc), dot(F_Schlick(s.f0, s.f90, s.NdotV), luma) * (1.0 - Fc), Fc);
    w /= max(w.x + w.y + w.z, 1e-6);
    w = max(w, vec3(0.1, 0.1, s.coat ? 0.1 : 0.0));
    s.lobeProbability = w / (w.x + w.y + w.z);

    vec3 luminance = g.emissive;
    uint count = rgLightCount();
    // Delta lights: no sampling, no noise.
    uint sampled = 0u;
    for (uint i = 0u; i < count; ++i) {
        RgLight light = rgLight(i);
        if (rgLightType(light) <= RG_LIGHT_SPOT) luminance += punctual(s, light);
        else ++sampled;
    }

    // Sampled lights: one BRDF sample shared by every light + one light sample per light, MIS.
    RgRng rng = rgRngInit(uvec4(uint(p.x), uint(p.y), frame, uint(params.reference_seed + 0.5)));
    const bool environment = textureSize(SceneEnvironment, 0).x > 1 || any(greaterThan(texelFetch(SceneEnvironment, ivec2(0), 0).rgb, vec3(0.0)));
    int samples = sampled > 0u || environment ? max(int(params.reference_samples + 0.5), 1) : 0;
    int strategy = int(params.reference_strategy + 0.5);
    vec3 sum = vec3(0.0);
    for (int k = 0; k < samples; ++k) {
        vec3 Lb;
        float pdfB = sampleBrdf(s, rng, Lb);
        vec3 fB = pdfB > 0.0 ? brdfCos(s, Lb) : vec3(0.0);
        bool useB = pdfB > 0.0 && any(greaterThan(fB, vec3(0.0)));
        vec3 estimate = vec3(0.0);
        if (environment) {
            // The environment's own sample (not with reference_strategy = brdf) ...
            vec3 Le;
            float pdfE = sampleEnvironment(rgRngNext2(rng), Le);
            if (pdfE > 0.0 && strategy != 2) {
                vec3 f = brdfCos(s, Le);
                if (any(greaterThan(f, vec3(0.0))) && unoccluded(s, Le, 1e30)) {
                    float weight = strategy == 1 ? 1.0 : rgPowerHeuristic(pdfE, brdfPdf(s, Le));
                    estimate += f * textureLod(SceneEnvironment, rgEquirectUv(Le), 0.0).rgb * (weight / pdfE);
                }
            }
            // ... and the BRDF's (not with reference_strategy = light).
            if (useB && strategy != 1 && unoccluded(s, Lb, 1e30)) {
                float weight = strategy == 2 ? 1.0 : rgPowerHeuristic(pdfB, envPdf(Lb));
                estimate += fB * textureLod(SceneEnvironment, rgEquirectUv(Lb), 0.0).rgb * (weight / pdfB);
            }
        }
        for (uint i = 0u; i < count; ++i) {
            RgLight light = rgLight(i);
            int type = rgLightType(light);
            if (type <= RG_LIGHT_SPOT) continue;
            vec3 Le = lightRadiance(light, type, s.P);
            // The light's sample.
            vec3 u = vec3(rgRngNext2(rng), rgRngNext(rng));
            vec3 Ll;
            float pdfL = sampleLight(light, type, s.P, u, Ll);
            if (pdfL > 0.0 && strategy != 2) {
                vec3 f = brdfCos(s, Ll);
                if (any(greaterThan(f, vec3(0.0))) && unoccluded(s, Ll, lightDistance(light, type, s.P, Ll))) {
                    float weight = strategy == 1 ? 1.0 : rgPowerHeuristic(pdfL, brdfPdf(s, Ll));
                    estimate += f * Le * (weight / pdfL);
                }
            }
            // The BRDF's sample, if its ray meets this light.
            if (useB && strategy != 1) {
                float pdfLB = lightPdfAlong(light, type, s.P, Lb);
                if (pdfLB > 0.0 && unoccluded(s, Lb, lightDistance(light, type, s.P, Lb))) {
                    float weight = strategy == 2 ? 1.0 : rgPowerHeuristic(pdfB, pdfLB);
                    estimate += fB * Le * (weight / pdfB);
                }
            }
        }
#ifdef RG_REFERENCE_SHOW_NAN
        if (!finite3(estimate)) { imageStore(hdr, p, vec4(65504.0, 0.0, 65504.0, 1.0)); return; }
#endif
        if (finite3(estimate)) sum += estimate;  // a non-finite sample would poison the running mean
    }
    if (samples > 0) luminance += sum / float(samples);

    vec3 mean = frame == 0u ? luminance : previous.rgb + (luminance - previous.rgb) / float(frame + 1u);
    imageStore(reference_accum, p, vec4(mean, float(frame + 1u)));
    imageStore(hdr, p, vec4(mean * pre, 1.0));
}

// Linearly transformed cosines for area lights (Heitz, Dupuy, Hill, Neubelt 2016; Heitz & Hill
// 2017 for disks and spheres): what a pipeline with area_lights = "ltc" (scripts/lighting.lua)
// evaluates in place of seed 002 §4.7's structured sampling and representative points. The GGX
// lobe of lib/brdf.glsl at a roughness and view angle is a clamped cosine seen through a matrix M;
// its integral over a light is the cosine's integral over the light transformed by M⁻¹ — a
// polygon's or an ellipse's form factor, in closed form, horizon included. The table (M⁻¹, and
// the lobe's albedo split for Schlick's Fresnel) is fitted by tools/ltc_fit.cpp
// (graph/lighting/ltc_ggx.inc) and travels in the Lights block (lib/scene.glsl). The CPU twins
// are graph/lighting/ltc.h's, which say what each part holds.
#ifndef RG_LTC_GLSL
#define RG_LTC_GLSL

#include "lib/scene.glsl"
#include "lib/brdf.glsl"

// The table entry at (linearRoughness, ⟨n·v⟩), bilinear between texel centres (ltc.h's lookup):
// the GGX lobe's M⁻¹ in the frame (T1, T2, N), T1 the view's tangent, and its albedo split for
// Schlick's Fresnel (magnitude − fresnel, fresnel).
void rgLtcLookup(float linearRoughness, float NdotV, out mat3 Minv, out vec2 albedo) {
    const float n = float(RG_LTC_SIZE - 1);
    vec2 t = vec2(clamp(linearRoughness, 0.0, 1.0), sqrt(clamp(1.0 - NdotV, 0.0, 1.0))) * n;
    ivec2 i0 = min(ivec2(t), ivec2(RG_LTC_SIZE - 2));
    vec2 w = t - vec2(i0);
    int k = 2 * (i0.y * RG_LTC_SIZE + i0.x), row = 2 * RG_LTC_SIZE;
    vec4 m = mix(mix(lights.ltc[k], lights.ltc[k + 2], w.x), mix(lights.ltc[k + row], lights.ltc[k + row + 2], w.x), w.y);
    vec4 a = mix(mix(lights.ltc[k + 1], lights.ltc[k + 3], w.x), mix(lights.ltc[k + row + 1], lights.ltc[k + row + 3], w.x), w.y);
    // [[a, 0, b], [0, 1, 0], [c, 0, d]] row-major; GLSL's mat3 takes columns.
    Minv = mat3(vec3(m.x, 0.0, m.z), vec3(0.0, 1.0, 0.0), vec3(m.y, 0.0, m.w));
    albedo = vec2(a.x - a.y, a.y);
}

// The world → (T1, T2, N) rotation of a shaded point.
mat3 rgLtcFrame(vec3 N, vec3 V) {
    vec3 t = V - N * dot(V, N);
    vec3 T1 = dot(t, t) > 1e-12 ? normalize(t) : normalize(cross(N, abs(N.y) < 0.99 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0)));
    vec3 T2 = cross(N, T1);
    return transpose(mat3(T1, T2, N));
}

// An edge's share of the vector form factor: the arc's angle along the unit normal of its plane.
vec3 rgLtcEdge(vec3 v1, vec3 v2) {
    vec3 c = cross(v1, v2);
    float s = length(c);
    return s > 1e-12 ? c * (atan(s, dot(v1, v2)) / s) : vec3(0.0);
}

// ∫ max(ω.z, 0)/π over the quad p0 p1 p2 p3 (in the cosine's space, relative to the shaded point):
// clipped to z > 0 (Sutherland–Hodgman), then the sum of its edges. `direction`: the clipped
// polygon's vector form factor (unnormalised; its mean direction, into the upper hemisphere).
float rgLtcQuad(vec3 p0, vec3 p1, vec3 p2, vec3 p3, out vec3 direction) {
    vec3 v[4] = vec3[4](p0, p1, p2, p3);
    vec3 c[5];
    int n = 0;
    for (int i = 0; i < 4; ++i) {
        vec3 a = v[i], b = v[(i + 1) & 3];
        if (a.z > 0.0) c[n++] = a;
        if ((a.z > 0.0) != (b.z > 0.0)) c[n++] = a + (b - a) * (a.z / (a.z - b.z));
    }
    vec3 sum = vec3(0.0);
    for (int i = 0; i < n; ++i) sum += rgLtcEdge(normalize(c[i]), normalize(c[i + 1 == n ? 0 : i + 1]));
    direction = sum.z < 0.0 ? -sum : sum;  // the winding decides the sign
    return abs(sum.z) * (0.5 / RG_PI);
}

// The unclipped quad's vector form factor over 2π, pointing towards the quad: its length is the
// sin²σ, its direction the axis, of the sphere with the same form factor (Hill & Heitz's
// equivalent sphere), which rgHorizonDisney takes for a quad that crosses the horizon.
vec3 rgLtcQuadVector(vec3 p0, vec3 p1, vec3 p2, vec3 p3) {
    vec3 v0 = normalize(p0), v1 = normalize(p1), v2 = normalize(p2), v3 = normalize(p3);
    vec3 sum = rgLtcEdge(v0, v1) + rgLtcEdge(v1, v2) + rgLtcEdge(v2, v3) + rgLtcEdge(v3, v0);
    return (dot(sum, p0 + p2) < 0.0 ? -sum : sum) * (0.5 / RG_PI);
}

float illuminanceSphereOrDisk(float cosTheta, float sinSigmaSqr);  // lib/lighting.glsl (seed 000 lst:10)

// A cone (unit axis, half-angle σ) that crosses the plane normal to `up`: the part above it seen
// as a band of elevations 0 < y < e + σ (e: the axis's elevation; small-angle model, the cone's
// section a disk of radius σ around e, so the band's width at y is w(y) = √(σ² − (y − e)²)),
// sampled at 8 elevations along the axis's azimuth (the midpoint rule), each weighted by
// w(y) sin y (its share of the cosine-weighted light). Returns the renormalised Disney diffuse
// (lst:1, without its 1/π) averaged over that part — not the term at the mean direction, which is
// off by its curvature near the horizon (too bright for a smooth surface, too dark for a rough
// one) — and gives in `meanDirection` the part's mean direction, where the diffuse lobe looks at the
// light. Wholly above the horizon (or below): the term at the axis, and the axis.
float rgHorizonDisney(vec3 axis, vec3 up, float sinSigma, vec3 V, float linearRoughness, out vec3 meanDirection) {
    float NdotV = abs(dot(up, V)) + 1e-5;  // lst:2, as rgDiffuseBrdf
    float sinE = clamp(dot(axis, up), -1.0, 1.0);
    float e = asin(sinE), sigma = asin(clamp(sinSigma, 0.0, 1.0)), top = e + sigma;
    vec3 level = axis - up * sinE;
    float l2 = dot(level, level);
    meanDirection = axis;
    if (e >= sigma || top <= 0.0 || l2 < 1e-12) {
        vec3 H = normalize(V + axis);
        return Fr_DisneyDiffuse(NdotV, clamp(sinE, 0.0, 1.0), clamp(dot(axis, H), 0.0, 1.0), linearRoughness);
    }
    level *= inversesqrt(l2);
    float disney = 0.0, elevation = 0.0, weights = 0.0;
    for (int i = 0; i < 8; ++i) {
        float y = top * (float(i) + 0.5) / 8.0;
        float w = sqrt(max(sigma * sigma - (y - e) * (y - e), 0.0)) * sin(y);
        vec3 L = level * cos(y) + up * sin(y);
        vec3 H = normalize(V + L);
        disney += w * Fr_DisneyDiffuse(NdotV, sin(y), clamp(dot(L, H), 0.0, 1.0), linearRoughness);
        elevation += w * y;
        weights += w;
    }
    if (weights <= 0.0) return 1.0;
    elevation /= weights;
    meanDirection = level * cos(elevation) + up * sin(elevation);
    return disney / weights;
}

// The same for the ellipse centre + cos t · axis1 + sin t · axis2 (any conjugate pair of half-axes):
// its cone of directions is an elliptic cone with tan² half-angles L1², L2² around an axis; the
// form factor of that cone, L1 L2 / √((1 + L1²)(1 + L2²)), is the sin²σ of the sphere whose
// horizon-clipped integral (lst:10) stands for the ellipse's. ltc.cpp's ellipseIntegral derives
// the quadric's smallest eigenvalue λ3 ∈ [−1, −1/(1 + x0² + y0²)], found here by bracketed Newton.
// `direction`, `sinSigmaSqr`: the axis and sin²σ of that sphere.
float rgLtcEllipse(vec3 centre, vec3 axis1, vec3 axis2, out vec3 direction, out float sinSigmaSqr) {
    float d11 = dot(axis1, axis1), d22 = dot(axis2, axis2), d12 = dot(axis1, axis2);
    vec3 t1 = axis1, t2 = axis2;
    float e1 = d11, e2 = d22;
    if (abs(d12) > 1e-4 * sqrt(d11 * d22)) {
        float mean = 0.5 * (d11 + d22), spread = sqrt(0.25 * (d11 - d22) * (d11 - d22) + d12 * d12);
        e1 = mean + spread;
        e2 = max(mean - spread, 0.0);
        t1 = d11 > d22 ? axis1 * d12 + axis2 * (e1 - d11) : axis1 * (e1 - d22) + axis2 * d12;
        t2 = cross(cross(axis1, axis2), t1);
    }
    t1 = normalize(t1);
    t2 = normalize(t2);
    vec3 t3 = cross(t1, t2);
    float h = dot(t3, centre);
    if (h < 0.0) { t3 = -t3; h = -h; }
    direction = vec3(0.0, 0.0, 1.0);
    sinSigmaSqr = 0.0;
    if (h < 1e-7 * sqrt(e1)) return 0.0;  // seen edge on
    float x0 = dot(t1, centre) / h, y0 = dot(t2, centre) / h;
    float a1s = e1 / (h * h), a2s = e2 / (h * h);
    float k3 = a1s * a2s, k2 = (1.0 + x0 * x0) * a2s + (1.0 + y0 * y0) * a1s - a1s * a2s;
    float k1 = 1.0 + x0 * x0 + y0 * y0 - a1s - a2s;
    float lo = -1.0, hi = -1.0 / (1.0 + x0 * x0 + y0 * y0), lambda = hi;
    for (int i = 0; i < 12; ++i) {
        float g = ((k3 * lambda - k2) * lambda + k1) * lambda + 1.0;
        if (g > 0.0) hi = lambda;
        else lo = lambda;
        float dg = (3.0 * k3 * lambda - 2.0 * k2) * lambda + k1;
        float next = dg != 0.0 ? lambda - g / dg : 0.5 * (lo + hi);
        lambda = next > lo && next < hi ? next : 0.5 * (lo + hi);
    }
    float productTan = -lambda * lambda * lambda * k3;
    float sumTan = lambda * lambda * (k2 - lambda * k3);
    float formFactor = sqrt(max(productTan, 0.0) / (1.0 + sumTan + productTan));
    direction = normalize(t1 * (x0 / (1.0 - lambda * a1s)) + t2 * (y0 / (1.0 - lambda * a2s)) + t3);
    sinSigmaSqr = min(formFactor, 0.9999);
    return illuminanceSphereOrDisk(clamp(direction.z, -0.9999, 0.9999), sinSigmaSqr) / RG_PI;
}

#endif

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
    vec4 m = mix(mix(lightTables.ltc[k], lightTables.ltc[k + 2], w.x), mix(lightTables.ltc[k + row], lightTables.ltc[k + row + 2], w.x), w.y);
    vec4 a = mix(mix(lightTables.ltc[k + 1], lightTables.ltc[k + 3], w.x), mix(lightTables.ltc[k + row + 1], lightTables.ltc[k + row + 3], w.x), w.y);
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

// Room for a polygon's vertices: a 16-gon clipped once (rgLtcEllipseHorizon).
#define RG_LTC_MAX_VERTICES 17

// ∫ max(ω.z, 0)/π over the polygon v[0..n) (in the cosine's space, relative to the shaded point):
// clipped to z > 0 (Sutherland–Hodgman) as its edges are walked, each kept or cut vertex closing
// an edge, then the sum of the edges. `direction`: the clipped polygon's vector form factor
// (unnormalised; its mean direction, into the upper hemisphere).
float rgLtcPolygon(vec3 v[RG_LTC_MAX_VERTICES], int n, out vec3 direction) {
    vec3 sum = vec3(0.0), first = vec3(0.0), previous = vec3(0.0);
    int m = 0;
    for (int i = 0; i < n; ++i) {
        vec3 a = v[i], b = v[i + 1 == n ? 0 : i + 1];
        if (a.z > 0.0) {
            vec3 q = normalize(a);
            if (m++ == 0) first = q; else sum += rgLtcEdge(previous, q);
            previous = q;
        }
        if ((a.z > 0.0) != (b.z > 0.0)) {
            vec3 q = normalize(a + (b - a) * (a.z / (a.z - b.z)));
            if (m++ == 0) first = q; else sum += rgLtcEdge(previous, q);
            previous = q;
        }
    }
    if (m > 1) sum += rgLtcEdge(previous, first);
    direction = sum.z < 0.0 ? -sum : sum;  // the winding decides the sign
    return abs(sum.z) * (0.5 / RG_PI);
}

// The quad p0 p1 p2 p3 (in the cosine's space).
float rgLtcQuad(vec3 p0, vec3 p1, vec3 p2, vec3 p3, out vec3 direction) {
    vec3 v[RG_LTC_MAX_VERTICES];
    v[0] = p0;
    v[1] = p1;
    v[2] = p2;
    v[3] = p3;
    return rgLtcPolygon(v, 4, direction);
}

// One Sutherland–Hodgman step against the shading horizon (z = 0 of the shaded point's frame) for
// the edge x → y, what it keeps taken through the table's M⁻¹ and appended to a[0..k).
void rgLtcKeepAbove(vec3 x, vec3 y, mat3 MinvTable, inout vec3 a[RG_LTC_MAX_VERTICES], inout int k) {
    if (x.z > 0.0) a[k++] = MinvTable * x;
    if ((x.z > 0.0) != (y.z > 0.0)) a[k++] = MinvTable * (x + (y - x) * (x.z / (x.z - y.z)));
}

// The GGX lobe's integral over the quad p0..p3 (in the shaded point's frame (T1, T2, N)): the quad
// clipped to the shading horizon first, then taken through the table's M⁻¹ and clipped to the
// cosine's horizon, the sum of its edges. The fitted D leaks below the shading horizon (M⁻¹ does
// not keep the plane z = 0), where GGX with ⟨n·l⟩ is 0: without the first clip a light crossing the
// floor's plane gets that leak as light. `direction`: the result's vector form factor, in the
// cosine's space.
float rgLtcQuadHorizon(vec3 p0, vec3 p1, vec3 p2, vec3 p3, mat3 MinvTable, out vec3 direction) {
    vec3 v[4] = vec3[4](p0, p1, p2, p3);
    vec3 a[RG_LTC_MAX_VERTICES];
    int k = 0;
    for (int i = 0; i < 4; ++i) rgLtcKeepAbove(v[i], v[(i + 1) & 3], MinvTable, a, k);
    return rgLtcPolygon(a, k, direction);
}

// The same for an ellipse (centre ± half-axes T, B, in the shaded point's frame) that crosses the
// shading horizon, as the 16-gon of its area (circumradius × √(2π / (16 sin(π/8))) = 1.01300):
// the closed form for ellipses (rgLtcEllipse) clips by an equivalent sphere, which the GGX lobe's
// leak below the horizon makes a few per cent bright on a glossy metal.
float rgLtcEllipseHorizon(vec3 centre, vec3 T, vec3 B, mat3 MinvTable, out vec3 direction) {
    const int n = 16;
    vec3 a[RG_LTC_MAX_VERTICES];
    int k = 0;
    vec3 x = centre + T * 1.01300;
    for (int i = 0; i < n; ++i) {
        float t = float(i + 1) * (2.0 * RG_PI / float(n));
        vec3 y = centre + (T * cos(t) + B * sin(t)) * 1.01300;
        rgLtcKeepAbove(x, y, MinvTable, a, k);
        x = y;
    }
    return rgLtcPolygon(a, k, direction);
}

// Whether the ellipse centre ± T, B (in the shaded point's frame) dips below the shading horizon.
bool rgLtcCrossesHorizon(vec3 centre, vec3 T, vec3 B) { return centre.z * centre.z <= T.z * T.z + B.z * B.z || centre.z <= 0.0; }

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

// ---- The lobe's shape, corrected at the light ---------------------------------------------------
// One 3×3 matrix cannot follow GGX's shape everywhere: on a glossy metal the fitted cosine is a few
// per cent off along the edge of a highlight (a light larger than the lobe, part of the lobe on
// it), where the integral is a partial one. After Heitz et al.'s ratio estimator (2018): the
// integral of the BRDF over the light is the closed form's times the ratio r(ω) = f(ω)⟨n·l⟩ /
// (albedo · D(ω)), which is 1 where the fit is exact, taken at the closed form's own mean direction
// (D's centroid over the light). Measured on the accuracy suite's glossy metal (mean error, sphere
// / disk / rect / tube, facing): 2.6 / 3.0 / 3.2 / 2.9 % without it, 1.0 / 1.0 / 1.5 / 1.6 % with
// it. Averaging r over 32 directions distributed as D that hit the light instead measured no
// better (sphere grazing 2.4 % against 2.2 %) at 32 times the cost. Minv: world → the cosine's
// space; albedo: the lobe's with F = 1; mean: the closed form's `direction` (cosine's space).
float rgLtcLobe(vec3 N, vec3 V, vec3 L, float alpha) {
    float NdotL = dot(N, L);
    if (NdotL <= 0.0) return 0.0;
    float NdotV = abs(dot(N, V)) + 1e-5;
    float NdotH = clamp(dot(N, normalize(V + L)), 0.0, 1.0);
    return D_GGX(NdotH, alpha) * V_SmithGGXCorrelated(NdotL, NdotV, alpha) / RG_PI * NdotL;  // rgSpecularBrdf, F = 1
}

float rgLtcRatio(mat3 Minv, vec3 N, vec3 V, float alpha, float albedo, vec3 mean) {
    float det = abs(determinant(Minv));
    if (albedo <= 0.0 || det <= 0.0 || dot(mean, mean) <= 0.0) return 1.0;
    vec3 L = normalize(inverse(Minv) * mean);
    // D(ω) = Do(M⁻¹ω / |M⁻¹ω|) · |det M⁻¹| / |M⁻¹ω|³, Do(o) = max(o.z, 0)/π.
    vec3 o = Minv * L;
    float lo2 = dot(o, o);
    float D = max(o.z, 0.0) * det / (RG_PI * lo2 * lo2);
    // Faded out as the direction nears either horizon (⟨n·l⟩ or its elevation in the cosine's space
    // below 0.25), where r changes too fast across the light for one direction to stand for it
    // (test_ltc: +24 % unfaded, +4.5 % faded, −10 % without, on a lobe's far tail) or D → 0 (the
    // axis of a partly clipped ellipse can lie just above the cosine's horizon: r without bound).
    float fade = smoothstep(0.0, 0.25, dot(N, L)) * smoothstep(0.0, 0.25, o.z * inversesqrt(lo2));
    return fade > 0.0 ? mix(1.0, rgLtcLobe(N, V, L, alpha) / (albedo * D), fade) : 1.0;
}

// The same correction for a sphere, whose light is a cap of directions (half-angle σ around L):
// the ratio of the lobe's integral over the cap to the fitted D's, both by one quadrature — 32
// directions of equal solid angle on a golden-angle spiral over the cap (cos θ_k = 1 − (1 − cos σ)
// (k + ½)/32) — so that where f/D varies across a cap larger than the lobe the ratio is D's
// average of it, not its value at one direction. Only points above the shading horizon count for
// D (the closed form is clipped there; the lobe is 0 below it). Measured on the accuracy suite's
// glossy metal by the CPU twin (ltc::sphereRatio, brute-force cap integral, mean relative error,
// facing / grazing / horizon): 0.64 / 1.92 / 3.5 % at the mean direction, 0.16 / 0.53 / 1.08 %
// with 16 directions, 0.08 / 0.26 / 0.50 % with 32. `albedo`: the lobe's with F = 1.
#define RG_LTC_SPHERE_TAPS 32
float rgLtcSphereRatio(mat3 Minv, vec3 N, vec3 V, float alpha, float albedo, vec3 L, float sinSigmaSqr) {
    float det = abs(determinant(Minv));
    if (albedo <= 0.0 || det <= 0.0) return 1.0;
    float oneMinusCos = 1.0 - sqrt(1.0 - sinSigmaSqr);
    vec3 t1 = normalize(cross(L, abs(L.y) < 0.99 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0))), t2 = cross(L, t1);
    float lobe = 0.0, fitted = 0.0;
    for (int k = 0; k < RG_LTC_SPHERE_TAPS; ++k) {
        float cosTheta = 1.0 - oneMinusCos * (float(k) + 0.5) / float(RG_LTC_SPHERE_TAPS);
        float sinTheta = sqrt(max(1.0 - cosTheta * cosTheta, 0.0));
        float phi = float(k) * 2.39996323;
        vec3 l = L * cosTheta + (t1 * cos(phi) + t2 * sin(phi)) * sinTheta;
        lobe += rgLtcLobe(N, V, l, alpha);
        vec3 o = Minv * l;
        float lo2 = dot(o, o);
        fitted += dot(N, l) > 0.0 ? max(o.z, 0.0) * det / (RG_PI * lo2 * lo2) : 0.0;
    }
    return fitted > 0.0 ? lobe / (albedo * fitted) : 1.0;
}

#endif

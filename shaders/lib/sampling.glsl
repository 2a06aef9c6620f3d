// Random numbers and sampling helpers for Monte Carlo passes (shaders/passes/reference.comp).
//
// Random numbers: a 32-bit PCG generator (O'Neill 2014: LCG state step, then the RXS-M-XS output
// permutation). Each (pixel, frame, seed) gets its own state by hashing those four words with the
// same PCG permutation used as a hash (Jarzynski & Olano 2020 recommend it for GPU seeding); a
// pass then draws consecutive numbers from that stream. Floats take the top 24 bits: [0, 1).
#ifndef RG_SAMPLING_GLSL
#define RG_SAMPLING_GLSL

#ifndef RG_PI
#define RG_PI 3.14159265358979
#endif

// The PCG step and output permutation as a stateless hash of one word.
uint rgPcgHash(uint v) {
    uint state = v * 747796405u + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

struct RgRng { uint state; };

// Seeds a stream from four words (e.g. pixel x, pixel y, frame, user seed); chained hashes so
// that neighbouring pixels and frames get unrelated streams.
RgRng rgRngInit(uvec4 key) {
    RgRng r;
    r.state = rgPcgHash(key.x + rgPcgHash(key.y + rgPcgHash(key.z + rgPcgHash(key.w))));
    return r;
}

uint rgRngNextUint(inout RgRng r) {
    uint state = r.state;
    r.state = state * 747796405u + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

float rgRngNext(inout RgRng r) { return float(rgRngNextUint(r) >> 8u) * (1.0 / 16777216.0); }
vec2 rgRngNext2(inout RgRng r) { float a = rgRngNext(r); return vec2(a, rgRngNext(r)); }

// ---- Frames -------------------------------------------------------------------------------------

// An orthonormal basis (t, b) around the unit vector n, continuous except at n.z = −1 (the sign
// flip of Frisvad's construction, written branch-free).
void rgBasis(vec3 n, out vec3 t, out vec3 b) {
    float s = n.z >= 0.0 ? 1.0 : -1.0;
    float a = -1.0 / (s + n.z);
    float c = n.x * n.y * a;
    t = vec3(1.0 + s * n.x * n.x * a, s * c, -s * n.x);
    b = vec3(c, s + n.y * n.y * a, -n.y);
}

vec3 rgToWorld(vec3 local, vec3 t, vec3 b, vec3 n) { return local.x * t + local.y * b + local.z * n; }

// ---- Directions ---------------------------------------------------------------------------------

// Cosine-weighted hemisphere around +z (pdf cos θ / π): a uniform disk point lifted.
vec3 rgSampleCosineHemisphere(vec2 u) {
    float r = sqrt(u.x), phi = 2.0 * RG_PI * u.y;
    return vec3(r * cos(phi), r * sin(phi), sqrt(max(0.0, 1.0 - u.x)));
}

// Uniform direction on the sphere (pdf 1 / 4π).
vec3 rgSampleSphere(vec2 u) {
    float z = 1.0 - 2.0 * u.x, r = sqrt(max(0.0, 1.0 - z * z)), phi = 2.0 * RG_PI * u.y;
    return vec3(r * cos(phi), r * sin(phi), z);
}

// Uniform direction in the cone around +z of half-angle θmax, given 1 − cos θmax (passed directly
// so tiny cones — the sun: 1 − cos σ ≈ 1e-5 — keep their precision). pdf 1 / (2π (1 − cos θmax)).
vec3 rgSampleCone(vec2 u, float oneMinusCosMax) {
    float oneMinusCos = u.x * oneMinusCosMax;
    float cosTheta = 1.0 - oneMinusCos;
    float sinTheta = sqrt(max(0.0, oneMinusCos * (2.0 - oneMinusCos)));
    float phi = 2.0 * RG_PI * u.y;
    return vec3(sinTheta * cos(phi), sinTheta * sin(phi), cosTheta);
}

// 1 − cos θ from sin² θ (θ ≤ π/2) without cancellation.
float rgOneMinusCosFromSinSqr(float sinSqr) {
    sinSqr = clamp(sinSqr, 0.0, 1.0);
    return sinSqr / (1.0 + sqrt(1.0 - sinSqr));
}

// ---- GGX (isotropic, α = linearRoughness²) ------------------------------------------------------

// The normalised GGX distribution D(h) (brdf.glsl's D_GGX carries no 1/π).
float rgGgxD(float NdotH, float alpha) {
    if (NdotH <= 0.0) return 0.0;
    float a2 = alpha * alpha;
    float f = (NdotH * a2 - NdotH) * NdotH + 1.0;
    return a2 / (RG_PI * f * f);
}

// A microfacet normal of GGX distributed as its visible normals from Ve (local frame, +z the
// normal, Ve.z > 0): Heitz's stretch, then the visible-normal distribution of the hemisphere
// configuration as a uniform spherical cap (Dupuy & Benyoub 2023).
vec3 rgSampleGgxVisibleNormal(vec3 Ve, float alpha, vec2 u) {
    vec3 Vh = normalize(vec3(alpha * Ve.x, alpha * Ve.y, Ve.z));
    float phi = 2.0 * RG_PI * u.x;
    float z = (1.0 - u.y) * (1.0 + Vh.z) - Vh.z;
    float sinTheta = sqrt(clamp(1.0 - z * z, 0.0, 1.0));
    vec3 Nh = vec3(sinTheta * cos(phi), sinTheta * sin(phi), z) + Vh;
    return normalize(vec3(alpha * Nh.x, alpha * Nh.y, max(Nh.z, 0.0)));
}

// pdf (solid angle) of the direction L = reflect(−V, H) when H is drawn from the visible normals:
// D_V(H) / (4 V·H) with D_V(H) = G1(V) ⟨V·H⟩ D(H) / (N·V), G1(V) = 2 N·V / (N·V + √(α² + (1 − α²)(N·V)²)),
// i.e. D(H) / (2 (N·V + √(α² + (1 − α²)(N·V)²))). NdotV > 0.
float rgGgxVisibleReflectionPdf(float NdotV, float NdotH, float VdotH, float alpha) {
    if (VdotH <= 0.0) return 0.0;
    float a2 = alpha * alpha;
    return rgGgxD(NdotH, alpha) / (2.0 * (NdotV + sqrt(a2 + (1.0 - a2) * NdotV * NdotV)));
}

// ---- Multiple importance sampling ---------------------------------------------------------------

// Veach's power heuristic (β = 2) for one sample of strategy f against one of strategy g.
float rgPowerHeuristic(float pdfF, float pdfG) {
    float f = pdfF * pdfF, g = pdfG * pdfG;
    return f + g > 0.0 ? f / (f + g) : 0.0;
}

#endif

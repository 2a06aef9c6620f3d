#version 460
// Environment filtering, step 2 (seed 002 §4.9.2): the specular pre-filtered cube. Mip m holds
// the radiance convolved with GGX for linear roughness r = (m / (mips − 1))², i.e. the seed's
// mipLevel = sqrt(α_lin) · mipCount, with N = V = R (the split-sum assumption). GGX importance
// sampling of the half vector, each sample weighted by N·L (the seed's LD term), and read from the
// source cube's mip chain at the level whose texel matches the sample's solid angle ("filtered
// importance sampling", Křivánek & Colbert 2008): few samples, no fireflies.
//
// The distant probe samples `env_smooth`, the environment without its hot texels (a sun; see
// env_hot.comp), and adds those exactly (rgHotTexels): importance sampling alone, reading coarse
// mips, smeared a sun 10⁴× brighter than the sky into directions its GGX tail barely reaches —
// up to +440 % against the exact pre-filter under a sun-lit HDRI (tests/gpu/test_ibl.cpp).
//
// With RG_PROBE_ARRAY (scripts/probes.lua) the same for every cube of the local probes' captures:
// `probe_radiance` → `probe_specular`, layer z = 6 · probe + face, alpha (the captured
// visibility) filtered with the radiance.
#include "lib/environment.glsl"
#include "lib/sampling.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
#ifdef RG_PROBE_ARRAY
#include "lib/probes.glsl"
layout(set = 0, binding = 0) uniform samplerCubeArray probe_radiance;
layout(set = 0, binding = 1, rgba16f) uniform writeonly image2DArray probe_specular;
#define env_specular probe_specular
int gCube = 0;
vec4 rgSource(vec3 d, float lod) { return textureLod(probe_radiance, vec4(d, float(gCube)), lod); }
int rgSourceSize() { return textureSize(probe_radiance, 0).x; }
int rgSourceLevels() { return textureQueryLevels(probe_radiance); }
#else
layout(set = 0, binding = 0) uniform samplerCube env_source;
layout(set = 0, binding = 1, rgba16f) uniform writeonly image2DArray env_specular;
layout(set = 0, binding = 2) uniform samplerCube env_smooth;
#define RG_HOT_CAPACITY 4096u
layout(set = 0, binding = 3, std430) readonly buffer env_hot { uint count; uint pad0, pad1, pad2; vec4 texel[2 * RG_HOT_CAPACITY]; } hot;
vec4 rgSource(vec3 d, float lod) { return vec4(textureLod(env_smooth, d, lod).rgb, 1.0); }
int rgSourceSize() { return textureSize(env_smooth, 0).x; }
int rgSourceLevels() { return textureQueryLevels(env_smooth); }
#define RG_HOT_TEXELS 1
#endif
layout(push_constant) uniform Constants { float rg_mip; float rg_mipCount; } pc;

// Samples per texel: 128, and for the distant probe 384 at 32² and 1024 in the mips of 16² and
// fewer (little cost), whose broad lobes read coarse mips where the smooth remainder's horizon
// still bleeds (qwantani at roughness 1: 13.5 % → 2 %; chinese_garden's branches against the sky
// at linear roughness 0.14, the 256² cube's 32² mip: 5.5 % → 2.6 %, tests/gpu/test_ibl.cpp).
// The local probes' many small cubes keep 128.
#ifdef RG_HOT_TEXELS
uint rgSamples(int size) { return size > 32 ? 128u : size > 16 ? 384u : 1024u; }
#else
uint rgSamples(int size) { return 128u; }
#endif

// ∫ D(h) (n·l) dl with v = n (dl = 4 (n·h) dh, n·l = 2 (n·h)² − 1): the normalisation the
// importance-sampled ratio Σ L (n·l) / Σ (n·l) divides by implicitly, in closed form
// (t = (n·h)², a = α² − 1: 4α² ∫ from ½ to 1 of (2t − 1) / (a t + 1)² dt). 4 for a mirror, 1 at α = 1.
float rgGgxCosineNorm(float alpha) {
    float a = alpha * alpha - 1.0;
    if (abs(a) < 1e-4) return 1.0;
    float f1 = 2.0 / (a * a) * log(a + 1.0) + (2.0 / a + 1.0) / (a * (a + 1.0));
    float fh = 2.0 / (a * a) * log(0.5 * a + 1.0) + (2.0 / a + 1.0) / (a * (0.5 * a + 1.0));
    return 4.0 * alpha * alpha * (f1 - fh);
}

// Hammersley point i of n (Van der Corput radical inverse in base 2).
vec2 hammersley(uint i, uint n) { return vec2((float(i) + 0.5) / float(n), float(bitfieldReverse(i)) * 2.3283064365386963e-10); }

void main() {
    ivec3 p = ivec3(gl_GlobalInvocationID);
    ivec2 size = imageSize(env_specular).xy;
    if (any(greaterThanEqual(p.xy, size))) return;
#ifdef RG_PROBE_ARRAY
    gCube = p.z / 6;
    if (uint(gCube) >= rgProbes.count.x) return;  // no probe there
#endif
    vec3 N = rgCubeDirection(uint(p.z % 6), (vec2(p.xy) + 0.5) / vec2(size));
    int mips = rgSourceLevels();
    float linearRoughness = pow(pc.rg_mip / max(pc.rg_mipCount - 1.0, 1.0), 2.0);
    float alpha = max(linearRoughness * linearRoughness, 1e-3);
    if (pc.rg_mip == 0.0) {  // a mirror: the source itself (its hot texels too), at the matching resolution
        float lod = log2(float(rgSourceSize()) / float(size.x));
#ifdef RG_HOT_TEXELS
        imageStore(env_specular, p, vec4(textureLod(env_source, N, lod).rgb, 1.0));
#else
        imageStore(env_specular, p, rgSource(N, lod));
#endif
        return;
    }
    vec3 t, b;
    rgBasis(N, t, b);
    float sourceSize = float(rgSourceSize());
    float texelSolidAngle = 4.0 * RG_PI / (6.0 * sourceSize * sourceSize);
    vec4 sum = vec4(0.0);
    float weight = 0.0;
    // A lobe far narrower than this mip's texel (half its weight within ~α of N; a texel spans 2 / size
    // at a face's centre) is a mirror at this resolution: a few samples find what 128 would.
    uint samples = alpha < 0.25 / float(size.x) ? 16u : rgSamples(size.x);
    for (uint i = 0u; i < samples; ++i) {
        vec2 u = hammersley(i, samples);
        // GGX half vector around N: cos²θ = (1 − u) / (1 + (α² − 1) u).
        float cosTheta = sqrt((1.0 - u.y) / (1.0 + (alpha * alpha - 1.0) * u.y));
        float sinTheta = sqrt(max(0.0, 1.0 - cosTheta * cosTheta));
        float phi = 2.0 * RG_PI * u.x;
        vec3 H = rgToWorld(vec3(sinTheta * cos(phi), sinTheta * sin(phi), cosTheta), t, b, N);
        vec3 L = reflect(-N, H);
        float NdotL = dot(N, L);
        if (NdotL <= 0.0) continue;
        // pdf(L) = D(H) (N·H) / (4 V·H) with V = N: D / 4. Solid angle of one sample 1 / (n pdf).
        float pdf = rgGgxD(cosTheta, alpha) * 0.25;
        float sampleSolidAngle = 1.0 / (float(samples) * pdf + 1e-6);
        float lod = clamp(0.5 * log2(sampleSolidAngle / texelSolidAngle), 0.0, float(mips - 1));
        sum += rgSource(L, lod) * NdotL;
        weight += NdotL;
    }
    vec4 filtered = sum / max(weight, 1e-6);
#ifdef RG_HOT_TEXELS
    // The hot texels, exactly: Σ L D(h) (n·l) Ω / ∫ D (n·l) dl.
    vec3 exact = vec3(0.0);
    for (uint i = 0u; i < min(hot.count, RG_HOT_CAPACITY); ++i) {
        vec4 dw = hot.texel[2u * i];
        float NdotL = dot(N, dw.xyz);
        if (NdotL <= 0.0) continue;
        float NdotH = dot(N, normalize(N + dw.xyz));
        exact += hot.texel[2u * i + 1u].rgb * (rgGgxD(NdotH, alpha) * NdotL * dw.w);
    }
    filtered.rgb += exact / rgGgxCosineNorm(alpha);
#endif
    imageStore(env_specular, p, filtered);
}

// Baked global illumination from the scene's SG lightmap (seed 003, "SG Lightmaps", "Lighting with
// SGs"; graph/bake/lightmap.h): per texel, N spherical Gaussians G_k(x) = A_k e^{λ (μ_k · x − 1)} of
// incoming radiance in the texel's tangent frame — the axes μ_k fixed on the golden-ratio spiral over
// the hemisphere, one fixed sharpness λ, only the amplitudes A_k stored (layers 0 .. N − 1 of
// SceneLightmap; layer N: the irradiance at the frame's normal, passes/gpu_scene.cpp). Included with RG_SCENE_LIGHTMAP (set by the GPU scene when it has a lightmap).
#ifndef RG_LIGHTMAP_GLSL
#define RG_LIGHTMAP_GLSL

#ifndef RG_SCENE_LIGHTMAP
#define RG_SCENE_LIGHTMAP 0
#endif

#if RG_SCENE_LIGHTMAP
#ifndef RG_LIGHTMAP_BINDING
#define RG_LIGHTMAP_BINDING 20
#endif
layout(set = 0, binding = RG_LIGHTMAP_BINDING) uniform sampler2DArray SceneLightmap;

// Axis k of n on the hemisphere's golden spiral (lighting::goldenSpiralAxes(n, true)): z from
// 1 − 1/2n down in steps of 1/n, the azimuth turning by the golden angle π (3 − √5).
vec3 rgLightmapAxis(int k) {
    float z = 1.0 - (float(k) + 0.5) / float(RG_LIGHTMAP_LOBES);
    float r = sqrt(max(0.0, 1.0 - z * z));
    float phi = 2.39996322972865 * float(k);
    return vec3(r * cos(phi), r * sin(phi), z);
}

// ∫ G_k G dω of lobe k (unit amplitude) and a unit SG of sharpness λ around unit `dir`: their
// product is one SG of sharpness λm = |λ_k μ_k + λ dir|, integrated in closed form,
// 2π / λm (1 − e^{−2 λm}) · e^{λm − λ_k − λ} (lighting::innerProduct).
float rgLightmapLobeProduct(int k, float lambda, vec3 dir) {
    float lm = max(length(RG_LIGHTMAP_SHARPNESS * rgLightmapAxis(k) + lambda * dir), 1e-4);
    return 6.28318530717959 / lm * (1.0 - exp(-2.0 * lm)) * exp(lm - RG_LIGHTMAP_SHARPNESS - lambda);
}

// ∫ G_k(x) max(0, n·x) dω for all lobes: the SG–cosine product of the seed's "Lighting with SGs",
// the clamped cosine as one SG (λc 2.133, Ac 1.17) and the closed-form integral of the two lobes'
// product, 2π A / λm (1 − e^{−2 λm}) · e^{λm − λ − λc} (lighting::irradiance). n in tangent space; lux.
vec3 rgLightmapIrradiance(vec2 uv, vec3 n) {
    const float lambdaC = 2.133, ampC = 1.17;
    vec3 e = vec3(0.0);
    for (int k = 0; k < RG_LIGHTMAP_LOBES; ++k) {
        e += texture(SceneLightmap, vec3(uv, float(k))).rgb * (ampC * rgLightmapLobeProduct(k, lambdaC, n));
    }
    return e;
}

// The shaded normal N in the tangent frame the baker used (lib/material.glsl's rgTangentFrame).
vec3 rgLightmapTangentNormal(vec3 N, vec3 normal, vec4 tangent, bool frontFacing) {
    return N * rgTangentFrame(normal, tangent, frontFacing);  // (N·t, N·b, N·n)
}

// The radiosity a surface sends out from the baked light (seed 000 tbl:2's GB3): irradiance at its
// shaded normal × its diffuse albedo / π × its AO, in nits.
// A material variant without a normal map (RG_TEXTURES bit 4 clear) shades with the interpolated
// normal, (0, 0, 1) in the frame: it reads the irradiance the GPU scene precomputed for it in the
// layer after the lobes — one fetch instead of N (on a CPU rasteriser the N-lobe sum costs ~40 ms
// per 1280×720 G-buffer).
vec3 rgLightmapRadiosity(RgSurface s, vec3 normal, vec4 tangent, vec2 lightmapUv, bool frontFacing) {
#if defined(RG_TEXTURES) && (RG_TEXTURES & 4) == 0
    vec3 e = texture(SceneLightmap, vec3(lightmapUv, float(RG_LIGHTMAP_LOBES))).rgb;
#else
    vec3 e = rgLightmapIrradiance(lightmapUv, rgLightmapTangentNormal(s.normal, normal, tangent, frontFacing));
#endif
    vec3 albedo = s.twoColour ? s.diffuseColor : s.baseColor * (1.0 - s.metalMask);
    return albedo * (1.0 / 3.14159265358979) * e * s.ao;
}

// The specular light of the lightmap (seed 003 "Lighting with SGs": "GGX = 3 SGs"): the GGX NDF as
// three SGs over the half vector — its shape 1 / (1 + t)², t = tan²θ_h / α², fitted once as
// Σ c_i e^{−b_i t} (b = 0.191, 0.909, 2.776; c = 0.0612, 0.4119, 0.5163; 1.0 % relative RMS over
// t in 0..40), i.e. sharpness λ_i = 2 b_i / α² near the normal — each warped to directions around the
// reflection (Wang et al. 2009's spherical warp: sharpness λ_i / (4 |n·v|)), integrated against the
// radiance SGs in closed form, and normalised by the same integral of a uniform 1-nit hemisphere
// (RG_LIGHTMAP_UNIT): the average radiance over the lobe's part above the horizon — the
// pre-filtered term ("LD") the distant probe's mips give, which the composition weights by the
// split-sum DFG. The lobes' ripple and the part of a wide lobe below the horizon cancel in the ratio.
// Tangent space; nits.
vec3 rgLightmapSpecular(RgSurface s, vec3 normal, vec4 tangent, vec2 lightmapUv, bool frontFacing, vec3 V) {
    mat3 frame = rgTangentFrame(normal, tangent, frontFacing);
    vec3 N = s.normal * frame, v = V * frame;  // tangent space
    float linearRoughness = 1.0 - s.smoothness;
    float alpha = max(linearRoughness * linearRoughness, 0.02);
    vec3 R = reflect(-v, N);
    const float ggxB[3] = float[](0.191, 0.909, 2.776), ggxC[3] = float[](0.0612, 0.4119, 0.5163);
    const float unit[RG_LIGHTMAP_LOBES] = RG_LIGHTMAP_UNIT;
    float warp = 2.0 / (alpha * alpha) / (4.0 * max(dot(N, v), 0.05));
    vec3 ld = vec3(0.0);
    float one = 0.0;
    for (int k = 0; k < RG_LIGHTMAP_LOBES; ++k) {
        float w = 0.0;
        for (int i = 0; i < 3; ++i) w += ggxC[i] * rgLightmapLobeProduct(k, ggxB[i] * warp, R);
        ld += texture(SceneLightmap, vec3(lightmapUv, float(k))).rgb * w;
        one += unit[k] * w;
    }
    return ld / max(one, 1e-6);
}

// The debug views (session.cpp, --view lightmap / sgN): what = 0 the irradiance at the shaded
// normal (lux), k + 1 lobe k's amplitude (nits).
vec3 rgLightmapView(int what, RgSurface s, vec3 normal, vec4 tangent, vec2 lightmapUv, bool frontFacing) {
    if (what == 0) return rgLightmapIrradiance(lightmapUv, rgLightmapTangentNormal(s.normal, normal, tangent, frontFacing));
    return texture(SceneLightmap, vec3(lightmapUv, float(what - 1))).rgb;
}
#endif

#endif

// Image-based lighting from the distant light probe (seed 002 §4.9.3, §4.10.2): the split-sum
// specular and the Disney diffuse, each fetched along the seed's dominant direction, with
// specular micro-occlusion (f90) and specular occlusion from AO. A lighting shader that includes
// this file with RG_IBL defined (scripts/ibl.lua's `ibl.lit`) reads the filtered probe
// (env_specular), its diffuse SH (env_sh) and the DFG table (dfg); without RG_IBL every
// function returns 0 and nothing is bound.
//
// Conventions: linearRoughness = 1 − smoothness; the seed's listings call α = linearRoughness²
// "roughness" (their dominant-direction fits take α); the DFG table is indexed by
// (N·V, linearRoughness) — shaders/ibl/dfg.comp.
#ifndef RG_IBL_GLSL
#define RG_IBL_GLSL

#include "lib/environment.glsl"

#ifndef RG_IBL_SET
#define RG_IBL_SET 0
#endif
#ifndef RG_IBL_BINDING
#define RG_IBL_BINDING 7  // env_specular, env_sh, dfg at 7, 8, 9
#endif
#define RG_DFG_SIZE 128.0

#ifdef RG_IBL
layout(set = RG_IBL_SET, binding = RG_IBL_BINDING) uniform samplerCube env_specular;
layout(set = RG_IBL_SET, binding = RG_IBL_BINDING + 1, std140) uniform env_sh { vec4 coefficients[9]; } rgEnvSh;
layout(set = RG_IBL_SET, binding = RG_IBL_BINDING + 2) uniform sampler2D dfg;
#endif

// §4.9.3, "a simple approximation performs better": lerp(N, R) by smoothness (not normalised:
// it fetches a cube map).
vec3 rgSpecularDominantDir(vec3 N, vec3 R, float alpha) {
    float smoothness = clamp(1.0 - alpha, 0.0, 1.0);
    float lerpFactor = smoothness * (sqrt(smoothness) + alpha);
    return mix(N, R, lerpFactor);
}

// §4.9.3: the Disney diffuse lobe leans towards V as the view grazes (a linear fit).
vec3 rgDiffuseDominantDir(vec3 N, vec3 V, float NdotV, float alpha) {
    float a = 1.02341 * alpha - 1.51174;
    float b = -0.511705 * alpha + 0.755868;
    float lerpFactor = clamp((NdotV * a + b) * alpha, 0.0, 1.0);
    return mix(N, V, lerpFactor);
}

// §4.10.2 (Lagarde's fit after Gotanda): specular occlusion from AO, view and roughness (α).
float rgSpecularOcclusion(float NdotV, float ao, float alpha) {
    return clamp(pow(NdotV + ao, exp2(-16.0 * alpha - 1.0)) - 1.0 + ao, 0.0, 1.0);
}

// The DFG table at (N·V, linearRoughness), clamped to texel centres at the edges.
vec3 rgDfg(float NdotV, float linearRoughness) {
#ifdef RG_IBL
    vec2 uv = clamp(vec2(NdotV, linearRoughness), vec2(0.5 / RG_DFG_SIZE), vec2(1.0 - 0.5 / RG_DFG_SIZE));
    return textureLod(dfg, uv, 0.0).xyz;
#else
    return vec3(0.0);
#endif
}

// The sheen lobe's directional albedo E at N·V for a sheen roughness (the table's w: D_Charlie ·
// V_Neubelt over the hemisphere, lib/brdf.glsl); 0 without the table (RG_IBL).
float rgSheenAlbedo(float NdotV, float sheenRoughness) {
#ifdef RG_IBL
    vec2 uv = clamp(vec2(NdotV, sheenRoughness), vec2(0.5 / RG_DFG_SIZE), vec2(1.0 - 0.5 / RG_DFG_SIZE));
    return textureLod(dfg, uv, 0.0).w;
#else
    return 0.0;
#endif
}

// The screen-space reflection of the shaded pixel (scripts/ssr.lua's `ssr` pass: rgb in nits, a
// its confidence), or none without RG_SSR.
#ifdef RG_SSR
#ifndef RG_SSR_BINDING
#define RG_SSR_BINDING 17
#endif
layout(set = 0, binding = RG_SSR_BINDING) uniform sampler2D ssr;
// `ssr` is traced at half resolution (one ray per 2×2 pixels: the march is the frame's most
// expensive loop) and filtered bilinearly back to the pixel.
vec4 rgScreenSpaceReflection() { return textureLod(ssr, gl_FragCoord.xy * camera.viewport.zw, 0.0); }
#else
vec4 rgScreenSpaceReflection() { return vec4(0.0); }
#endif

// Local light probes (RG_PROBES, scripts/probes.lua's probes.lit): the scene's probes and their
// pre-filtered captures, cube k for probe k.
#ifdef RG_PROBES
#include "lib/probes.glsl"
#ifndef RG_PROBE_SPECULAR_BINDING
#define RG_PROBE_SPECULAR_BINDING 23
#endif
layout(set = 0, binding = RG_PROBE_SPECULAR_BINDING) uniform samplerCubeArray probe_specular;
#endif

// §4.9.5's composition of the reflected radiance along the dominant direction Rd from P: the
// screen-space reflection first (RG_SSR), then the local probes holding P from the first in the
// scene's order (RG_PROBES: priority, then the smaller) "until Alpha reaches 1", each weighted
// a = saturate(probe.a − Alpha) as the seed's listing does — probe.a its captured visibility
// along the lobe times its influence (appendix F) — then the distant probe's `distant` for the rest.
vec3 rgComposeReflection(vec3 P, vec3 Rd, float linearRoughness, vec3 distant, out float covered) {
    vec4 reflection = rgScreenSpaceReflection();
    vec3 rgb = reflection.rgb * reflection.a;
    float alpha = reflection.a;
#ifdef RG_PROBES
    float mips = float(textureQueryLevels(probe_specular));
    vec3 R = normalize(Rd);
    // A constant bound (the scene's probe count, RG_SCENE_PROBES): a CPU rasteriser runs a loop's
    // body at least once even when no lane enters it, and a scene without probes compiles none.
    for (uint k = 0u; k < uint(RG_SCENE_PROBES); ++k) {
        if (k >= rgProbes.count.x || alpha >= 1.0) break;
        RgProbe probe = rgProbes.probe[k];
        float influence = rgProbeInfluence(probe, P);
        vec3 direction;
        float localRoughness;
        if (influence <= 0.0 || !rgProbeParallax(probe, P, R, linearRoughness, direction, localRoughness)) continue;
        vec4 captured = textureLod(probe_specular, vec4(direction, float(k)), sqrt(localRoughness) * (mips - 1.0));
        float a = clamp(captured.a * influence - alpha, 0.0, 1.0);
        rgb += captured.rgb / max(captured.a, 1e-4) * a;  // the capture's radiance is 0 where it saw nothing
        alpha = clamp(alpha + a, 0.0, 1.0);
    }
#endif
    covered = alpha;
    return rgb + distant * (1.0 - alpha);
}
vec3 rgComposeReflection(vec3 P, vec3 Rd, float linearRoughness, vec3 distant) {
    float covered;
    return rgComposeReflection(P, Rd, linearRoughness, distant, covered);
}

// The composition pass's result for the shaded pixel (RG_REFLECTION, scripts/reflections.lua's
// reflections.lit: `reflection`, the composed radiance along the dominant direction of the
// pixel's G-buffer normal and roughness, in nits).
#ifdef RG_REFLECTION
#ifndef RG_REFLECTION_BINDING
#define RG_REFLECTION_BINDING 25
#endif
layout(set = 0, binding = RG_REFLECTION_BINDING) uniform sampler2D reflection;
#endif

// The distant probe's pre-filtered radiance along Rd for a linear roughness: the mip of
// sqrt(linearRoughness) (env_prefilter.comp).
#ifdef RG_IBL
vec3 rgDistantSpecular(vec3 Rd, float linearRoughness) {
    float mips = float(textureQueryLevels(env_specular));
    return textureLod(env_specular, Rd, sqrt(linearRoughness) * (mips - 1.0)).rgb;
}
#endif

// The probes' lighting of one lobe pair at P, before occlusion: diffuse (LD · DFG.z, the radiance
// reflected by a white Disney diffuse, from the distant probe) and specular (LD · (f0 DFG.x + f90
// DFG.y), LD composed from SSR, the local probes and the distant probe), both in cd/m² for an
// environment in nits.
struct RgIbl { vec3 diffuse; vec3 specular; };

// `pixelLobe`: the lobe of the pixel's own G-buffer normal and roughness, whose composed radiance
// the composition pass wrote (RG_REFLECTION); any other lobe (a clear coat's) composes its own.
RgIbl rgEvaluateIblLobe(vec3 P, vec3 N, vec3 V, vec3 f0, float f90, float linearRoughness, bool pixelLobe) {
    RgIbl r;
    r.diffuse = vec3(0.0);
    r.specular = vec3(0.0);
#ifdef RG_IBL
    float NdotV = max(dot(N, V), 0.5 / RG_DFG_SIZE);
    float alpha = linearRoughness * linearRoughness;
    vec3 R = reflect(-V, N);
    vec3 dfgTerms = rgDfg(NdotV, linearRoughness);
    // Diffuse: irradiance / π is the radiance a white Lambertian reflects; DFG.z turns it into the
    // renormalised Disney diffuse's.
    vec3 Nd = normalize(rgDiffuseDominantDir(N, V, NdotV, alpha));
#if defined(RG_SCENE_LIGHTMAP) && RG_SCENE_LIGHTMAP
    // The baked lightmap holds the environment's diffuse light (and its bounces) as radiosity
    // (lib/lightmap.glsl, added to the emission by the G-buffer pass).
    r.diffuse = vec3(0.0);
#else
    r.diffuse = rgShIrradiance(rgEnvSh.coefficients, Nd) / RG_PI * dfgTerms.z;
#endif
    // Specular: along the dominant direction.
    vec3 Rd = rgSpecularDominantDir(N, R, alpha);
    vec3 ld;
#ifdef RG_REFLECTION
    if (pixelLobe) ld = texelFetch(reflection, ivec2(gl_FragCoord.xy), 0).rgb;  // §4.9.5, composed by its own pass
    else
#endif
    {
        // §4.9.5: SSR, the local probes, then the distant probe, through the same split-sum weight.
        ld = rgComposeReflection(P, Rd, linearRoughness, rgDistantSpecular(Rd, linearRoughness));
    }
    r.specular = ld * (f0 * dfgTerms.x + f90 * dfgTerms.y);
#endif
    return r;
}
// Any lobe, composed here.
RgIbl rgEvaluateIbl(vec3 P, vec3 N, vec3 V, vec3 f0, float f90, float linearRoughness) {
    return rgEvaluateIblLobe(P, N, V, f0, f90, linearRoughness, false);
}

// The ambient occlusion of the shaded pixel at world position P: the material's, or with RG_SSAO
// (scripts/ao.lua's ao.lit) the smaller of it and the screen-space AO (seed 002 §4.10.3: combined
// by min), upsampled here from the filtered half-resolution AO by view distance (lib/upsample.glsl;
// the same as the `ssao` view's, without a full-resolution pass between).
#ifdef RG_SSAO
#include "lib/upsample.glsl"  // and `ao_filtered`
float rgAmbientOcclusion(float materialAo, vec3 P) {
    return min(materialAo, rgUpsampleHalf4(ao_filtered, ivec2(gl_FragCoord.xy), rgViewDepth(P)).r);
}
#else
float rgAmbientOcclusion(float materialAo, vec3 P) { return materialAo; }
#endif

// The standard material's ambient light: diffuse × colour × AO, specular × specular occlusion.
vec3 rgStandardIbl(vec3 P, vec3 N, vec3 V, vec3 diffuseColor, vec3 f0, float linearRoughness, float ao) {
    float f90 = clamp(50.0 * dot(f0, vec3(0.33)), 0.0, 1.0);  // as rgStandardBrdf (§4.10.2)
    RgIbl ibl = rgEvaluateIblLobe(P, N, V, f0, f90, linearRoughness, true);
    float NdotV = max(dot(N, V), 0.0);
    return diffuseColor * ibl.diffuse * ao + ibl.specular * rgSpecularOcclusion(NdotV, ao, linearRoughness * linearRoughness);
}

#endif

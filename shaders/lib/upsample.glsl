// Depth-aware (bilateral) upsampling of a signal computed at half resolution, read where a
// full-resolution pass needs it (the deferred lighting's sun shadow mask, lib/shadows.glsl, and
// screen-space AO, lib/ibl.glsl; the `ssao` view's pass).
// Texel h of the half-resolution target holds, in r, the signal at full-resolution pixel 2h and,
// in g, that pixel's view distance (m; 0 where nothing was computed: the clear). A pixel p takes
// the four texels around p / 2 — its own sample exactly at even pixels, the mean of two or four
// neighbours between them — each weighted bilinearly and by how close its view distance is to
// the pixel's, so that a value does not cross a silhouette: a tap from another surface falls to
// weight ~0 and the taps of the pixel's own surface carry it.
#ifndef RG_UPSAMPLE_GLSL
#define RG_UPSAMPLE_GLSL

// Every channel of the texels weighed (rg16f targets read b = 0, a = 1): a target that carries two
// signals beside the distance (the AO's with the sun's visibility in b, scripts/ao.lua) is upsampled
// once for both — two calls with the same arguments are one after the compiler's common
// subexpression elimination.
vec4 rgUpsampleHalf4(sampler2D halfRes, ivec2 pixel, float viewDistance) {
    ivec2 last = textureSize(halfRes, 0) - 1;
    vec2 f = vec2(pixel) * 0.5;  // texel h's sample sits at pixel 2h
    ivec2 base = ivec2(f);
    vec2 w1 = f - vec2(base), w0 = 1.0 - w1;
    // A relative tolerance: a floor seen at a grazing angle changes distance quickly per pixel.
    float falloff = 1.0 / (0.05 * viewDistance + 0.05);
    vec4 t00 = texelFetch(halfRes, min(base, last), 0);
    vec4 t10 = texelFetch(halfRes, min(base + ivec2(1, 0), last), 0);
    vec4 t01 = texelFetch(halfRes, min(base + ivec2(0, 1), last), 0);
    vec4 t11 = texelFetch(halfRes, min(base + ivec2(1, 1), last), 0);
    vec4 w = vec4(w0.x * w0.y, w1.x * w0.y, w0.x * w1.y, w1.x * w1.y) *
             (exp(-abs(vec4(t00.g, t10.g, t01.g, t11.g) - viewDistance) * falloff) + 1e-4);
    return (w.x * t00 + w.y * t10 + w.z * t01 + w.w * t11) / dot(w, vec4(1.0));
}
float rgUpsampleHalf(sampler2D halfRes, ivec2 pixel, float viewDistance) { return rgUpsampleHalf4(halfRes, pixel, viewDistance).r; }

// The filtered half-resolution AO a lighting pass reads with RG_SSAO (scripts/ao.lua's ao.lit;
// lib/ibl.glsl's rgAmbientOcclusion), declared here for lib/shadows.glsl too: with RG_SSAO_SUN it
// carries the sun's half-resolution visibility in b, and rgSunVisibility upsamples it from there.
#ifdef RG_SSAO
#ifndef RG_SSAO_BINDING
#define RG_SSAO_BINDING 16
#endif
layout(set = 0, binding = RG_SSAO_BINDING) uniform sampler2D ao_filtered;
#endif

#endif

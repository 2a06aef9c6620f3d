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

float rgUpsampleHalf(sampler2D halfRes, ivec2 pixel, float viewDistance) {
    ivec2 last = textureSize(halfRes, 0) - 1;
    vec2 f = vec2(pixel) * 0.5;  // texel h's sample sits at pixel 2h
    ivec2 base = ivec2(f);
    vec2 w1 = f - vec2(base), w0 = 1.0 - w1;
    // A relative tolerance: a floor seen at a grazing angle changes distance quickly per pixel.
    float falloff = 1.0 / (0.05 * viewDistance + 0.05);
    vec2 t00 = texelFetch(halfRes, min(base, last), 0).rg;
    vec2 t10 = texelFetch(halfRes, min(base + ivec2(1, 0), last), 0).rg;
    vec2 t01 = texelFetch(halfRes, min(base + ivec2(0, 1), last), 0).rg;
    vec2 t11 = texelFetch(halfRes, min(base + ivec2(1, 1), last), 0).rg;
    vec4 w = vec4(w0.x * w0.y, w1.x * w0.y, w0.x * w1.y, w1.x * w1.y) *
             (exp(-abs(vec4(t00.g, t10.g, t01.g, t11.g) - viewDistance) * falloff) + 1e-4);
    return dot(w, vec4(t00.r, t10.r, t01.r, t11.r)) / dot(w, vec4(1.0));
}

#endif

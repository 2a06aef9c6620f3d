// Which full-resolution pixel of its 2×2 block a half-resolution SSR texel traces from
// (ssr_mask.frag and ssr.frag agree on it). With RG_SSR_TEMPORAL the pixel turns through the
// block, one corner a frame — the diagonal first, so two frames already span the block — counted
// from the first frame or the last camera cut (Camera.temporal.y); `ssr_temporal` accumulates the
// four into the block's reflection. Without it, the top-left pixel every frame.
#ifndef RG_SSR_PIXEL_GLSL
#define RG_SSR_PIXEL_GLSL

// `size`: the full-resolution target's, so that an odd width or height reads its last pixel again
// rather than past it.
ivec2 rgSsrTracedPixel(ivec2 texel, ivec2 size) {
#ifdef RG_SSR_TEMPORAL
    const ivec2 corner[4] = ivec2[](ivec2(0, 0), ivec2(1, 1), ivec2(1, 0), ivec2(0, 1));
    return min(texel * 2 + corner[int(camera.temporal.y + 0.5) & 3], size - 1);
#else
    return min(texel * 2, size - 1);
#endif
}

#endif

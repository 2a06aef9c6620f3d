#version 460
// A depth pyramid (Hi-Z) through the compute kind's per-mip chain: each further mip the nearest
// (minimum) depth of the texels it covers in the one before — read through `hiz_previous`, 3 wide
// where the level before is odd so no texel is skipped. SSR's (seed 002 §4.9.4, Uludağ 2014): mip 0
// the depth buffer; ray marches skip a whole cell when the ray is in front of its nearest depth.
//
// RG_HIZ_FARTHEST (the G-buffer's occlusion culling, scripts/culling.lua): the farthest (maximum)
// depth instead, and mip 0 may be smaller than the depth buffer — texel p then covers every depth
// texel from floor(p · D / H) to ceil((p + 1) · D / H) − 1 (D, H: the two sizes), so a box whose
// nearest depth lies beyond a texel's is behind everything drawn over the pixels it covers.
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 0) uniform sampler2D depth;
layout(set = 0, binding = 1, r32f) uniform image2D hiz;
layout(set = 0, binding = 2) uniform sampler2D hiz_previous;
layout(push_constant) uniform Constants { float rg_mip; } pc;

#ifdef RG_HIZ_FARTHEST
#define rgHizJoin max
#else
#define rgHizJoin min
#endif

// Mip m > 0: the nearest (farthest) of the texels of mip m − 1 that texel p covers.
float rgHizPrevious(ivec2 p, ivec2 size, float d) {
    ivec2 prev = textureSize(hiz_previous, 0);
    ivec2 extra = ivec2(prev.x > 2 * size.x ? 2 : 1, prev.y > 2 * size.y ? 2 : 1);
    for (int j = 0; j <= extra.y; ++j)
        for (int i = 0; i <= extra.x; ++i) d = rgHizJoin(d, texelFetch(hiz_previous, min(2 * p + ivec2(i, j), prev - 1), 0).r);
    return d;
}

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(hiz);
    if (any(greaterThanEqual(p, size))) return;
#ifdef RG_HIZ_FARTHEST
    float d = 0.0;
    if (pc.rg_mip < 0.5) {
        const ivec2 full = textureSize(depth, 0);
        const ivec2 lo = p * full / size, hi = ((p + 1) * full + size - 1) / size;
        // 2 × 2 texels a gather (a quarter of the fetches); where the block's width or height is
        // odd the last gathers take a texel of the next block too (or the edge's again, clamped):
        // the farthest of more texels, still beyond every one of the block's.
        const vec2 texel = 1.0 / vec2(full);
        for (int y = lo.y; y < hi.y; y += 2)
            for (int x = lo.x; x < hi.x; x += 2) {
                const vec4 g = textureGather(depth, vec2(x + 1, y + 1) * texel, 0);
                d = max(d, max(max(g.x, g.y), max(g.z, g.w)));
            }
    } else {
        d = rgHizPrevious(p, size, 0.0);
    }
#else
    // SSR's: mip 0 the depth buffer itself (the same size).
    float d;
    if (pc.rg_mip < 0.5)
        d = texelFetch(depth, p, 0).r;
    else
        d = rgHizPrevious(p, size, 1.0);
#endif
    imageStore(hiz, p, vec4(d));
}

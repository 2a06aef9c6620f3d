// FXAA's luma and its local-contrast test, shared by fxaa.frag and fxaa_edges.frag so that the
// mask and the filter agree pixel for pixel. Expects `sampler2D source` (the display image).
#ifndef RG_FXAA_CONTRAST_GLSL
#define RG_FXAA_CONTRAST_GLSL

float luma(vec3 c) { return dot(c, vec3(0.299, 0.587, 0.114)); }
// The 3×3 neighbourhood sits on texel centres: unfiltered fetches (a filtered tap costs a CPU
// rasteriser four fetches and their blend).
ivec2 pixel, last;
float lumaNear(int dx, int dy) { return luma(texelFetch(source, clamp(pixel + ivec2(dx, dy), ivec2(0), last), 0).rgb); }
// The luma of the centre `pixel` (m) and of its four neighbours, their largest (hi) and their
// range (largest − smallest); `pixel` and `last` set first.
struct FxaaCross { float m, n, s, w, e, hi, range; };
FxaaCross fxaaCross(float m) {
    FxaaCross c;
    c.m = m;
    c.n = lumaNear(0, -1);
    c.s = lumaNear(0, 1);
    c.w = lumaNear(-1, 0);
    c.e = lumaNear(1, 0);
    c.hi = max(m, max(max(c.n, c.s), max(c.w, c.e)));
    c.range = c.hi - min(m, min(min(c.n, c.s), min(c.w, c.e)));
    return c;
}
// Whether the cross spans enough luma to be an edge worth filtering.
bool fxaaEdge(FxaaCross c, float threshold) { return c.range >= max(0.0312, c.hi * threshold); }

#endif

// FXAA's luma and its local-contrast test, shared by fxaa.frag and fxaa_edges.frag so that the
// mask and the filter agree pixel for pixel. Expects `sampler2D source` (the display image).
#ifndef RG_FXAA_CONTRAST_GLSL
#define RG_FXAA_CONTRAST_GLSL

float luma(vec3 c) { return dot(c, vec3(0.299, 0.587, 0.114)); }
// The 3×3 neighbourhood sits on texel centres: unfiltered fetches (a filtered tap costs a CPU
// rasteriser four fetches and their blend).
ivec2 pixel, last;
float lumaNear(int dx, int dy) { return luma(texelFetch(source, clamp(pixel + ivec2(dx, dy), ivec2(0), last), 0).rgb); }
// Whether the centre and its four neighbours span enough luma to be an edge worth filtering:
// `hi` their largest luma, `range` largest − smallest.
bool fxaaEdge(float hi, float range, float threshold) { return range >= max(0.0312, hi * threshold); }

#endif

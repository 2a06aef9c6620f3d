#version 460
// The half-resolution AO (gtao.frag) filtered at half resolution: a 4×4 box of texels around
// each (it averages gtao's 4×4 rotation pattern), each weighted by how close its view distance
// (kept by gtao beside the AO) is to the texel's own — a bilateral filter, so no AO bleeds across
// silhouettes. ao_upsample.frag then brings it to full resolution. Filtering here rather than
// per full-resolution pixel reads a quarter of the taps (22 → ~6 ms at 1280×720 on lavapipe).
layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 color;
layout(set = 0, binding = 0) uniform sampler2D ao_half;
// RG_AO_SUN (scripts/ao.lua): the sun's half-resolution visibility, copied into b at each texel
// (the same pixel 2h), for the lighting to upsample with the AO.
#ifdef RG_AO_SUN
layout(set = 0, binding = 1) uniform sampler2D sun_visibility_half;
#endif

void main() {
    ivec2 h = ivec2(gl_FragCoord.xy);
    ivec2 halfSize = textureSize(ao_half, 0);
    // The view distance of the texel: it has geometry (the pass is depth-tested over ao_mask,
    // scripts/ao.lua; the others keep the clear).
    float d0 = texelFetch(ao_half, h, 0).g;
#ifdef RG_AO_SUN
    float sun = texelFetch(sun_visibility_half, h, 0).r;
#else
    float sun = 1.0;
#endif
    float sum = 0.0, weight = 0.0;
    float falloff = 1.0 / (0.05 * d0 + 0.05);  // loose enough for a floor at grazing view
    for (int j = -2; j < 2; ++j)
        for (int i = -2; i < 2; ++i) {
            vec2 aoDepth = texelFetch(ao_half, clamp(h + ivec2(i, j), ivec2(0), halfSize - 1), 0).rg;
            float w = exp(-abs(aoDepth.g - d0) * falloff) + 1e-4;
            sum += aoDepth.r * w;
            weight += w;
        }
    color = vec4(sum / weight, d0, sun, 1.0);
}

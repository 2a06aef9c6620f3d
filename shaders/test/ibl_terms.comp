#version 460
// Seed 002's IBL terms as the lighting compiles them (tests/gpu/test_ibl_terms.cpp checks them
// against the seed's listings, computed on the CPU): per texel (u, v) = its centre in [0, 1]²,
//   r: §4.10.2 computeSpecOcclusion(N·V = u, AO = v, α = 0.1) — rgSpecularOcclusion
//   g: the same at α = 0.6
//   b: §4.9.3 computeDistanceBaseRoughness(4u, 0.25 + 3v, linear roughness 0.3)
//   a: the local roughness appendix F's parallax gives a point P = (3u − 1.5, 3v − 1.5, 0.4) inside
//      a sphere probe of radius 2 at the origin, reflecting along normalize(1, 0.3, −0.2) with
//      linear roughness 0.4 (the ray's exit distance and the exit point's distance from the centre)
#define RG_NO_PROBE_BINDING
#include "lib/ibl.glsl"
#include "lib/probes.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 0, rgba32f) uniform writeonly image2D terms;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(terms);
    if (p.x >= size.x || p.y >= size.y) return;
    vec2 uv = (vec2(p) + 0.5) / vec2(size);
    RgProbe probe;
    probe.positionShape = vec4(0.0, 0.0, 0.0, 0.0);  // a sphere at the origin
    probe.extentFade = vec4(2.0, 2.0, 2.0, 0.5);
    probe.axes[0] = vec4(1, 0, 0, 0);
    probe.axes[1] = vec4(0, 1, 0, 0);
    probe.axes[2] = vec4(0, 0, 1, 0);
    probe.influence = vec4(2.0, 2.0, 2.0, 0.0);
    vec3 direction;
    float local = -1.0;
    rgProbeParallax(probe, vec3(3.0 * uv - 1.5, 0.4), normalize(vec3(1.0, 0.3, -0.2)), 0.4, direction, local);
    imageStore(terms, p, vec4(rgSpecularOcclusion(uv.x, uv.y, 0.1), rgSpecularOcclusion(uv.x, uv.y, 0.6),
                              rgDistanceBasedRoughness(4.0 * uv.x, 0.25 + 3.0 * uv.y, 0.3), local));
}

#version 460
// Image-based lights composition (seed 002 §4.9.5), as a pass of its own: for every pixel with
// geometry, the specular radiance reflected along the dominant direction of its G-buffer normal
// and roughness (decoded with the pixel's material's layout: rgGBufferNormalAt) — the screen-space
// reflection first (RG_SSR), then the local probes holding the point by priority until Alpha
// reaches 1 (RG_PROBES, appendix F's parallax and fade), then the distant probe for the rest —
// in nits, composed once, for every lighting path to weight by its split-sum DFG (lib/ibl.glsl,
// RG_REFLECTION). Alpha: how much of it SSR and the local probes covered (the rest is the distant
// probe's). Pixels without geometry get 0.
#include "lib/scene.glsl"
#include "lib/ibl.glsl"
#define RG_GBUFFER_BINDING 40  // GB0..GB3 and depth_stencil: the pixel decoded by its material
#include "gbuffer_pipeline.glsl"

layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 color;
layout(set = 0, binding = 1) uniform sampler2D depth;
// The baked lightmap's specular radiance (lib/lightmap.glsl, written by the G-buffer pass when the
// pipeline's G-buffer has it: RG_LIGHTMAP_SPECULAR): with a scene lightmap, what the rest of the
// reflection takes instead of the distant probe, unless the lightmap_specular parameter is off.
#if defined(RG_LIGHTMAP_SPECULAR) && defined(RG_SCENE_LIGHTMAP) && RG_SCENE_LIGHTMAP
#define RG_USE_LIGHTMAP_SPECULAR 1
layout(set = 0, binding = 26) uniform sampler2D lightmap_specular;
layout(set = 0, binding = 27) uniform Params { float lightmap_specular; } params;
#endif

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    float z = texelFetch(depth, p, 0).r;
    color = vec4(0.0);
    if (z >= 1.0) return;
    vec3 P = rgWorldPosition(uv, z);
    vec3 N = rgGBufferNormalAt(p);
    vec3 V = rgViewDirection(P);
    float linearRoughness = 1.0 - rgGBufferSmoothnessAt(p);
    vec3 Rd = rgSpecularDominantDir(N, reflect(-V, N), linearRoughness * linearRoughness);
    float covered;
#ifdef RG_USE_LIGHTMAP_SPECULAR
    vec3 rest = params.lightmap_specular > 0.5 ? texelFetch(lightmap_specular, p, 0).rgb : rgDistantSpecular(Rd, linearRoughness);
#else
    vec3 rest = rgDistantSpecular(Rd, linearRoughness);
#endif
    vec3 ld = rgComposeReflection(P, Rd, linearRoughness, rest, covered);
    color = vec4(ld, covered);
}

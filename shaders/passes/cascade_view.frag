#version 460
// The `cascades` debug view: each pixel in the colour of the sun's shadow cascade it reads
// (red, green, blue, yellow from near to far; grey beyond the shadow distance), darkened where the
// sun is shadowed (lib/shadows.glsl's rgSunShadow). Nothing drawn: black.
#define RG_SHADOWS 1
#include "lib/scene.glsl"
#include "lib/shadows.glsl"
#define RG_GBUFFER_BINDING 40  // GB0..GB3 and depth_stencil: the pixel decoded by its material
#include "gbuffer_pipeline.glsl"

layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 color;
layout(set = 0, binding = 1) uniform sampler2D depth;

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    float z = texelFetch(depth, p, 0).r;
    if (z >= 1.0) { color = vec4(0.0, 0.0, 0.0, 1.0); return; }
    vec3 P = rgWorldPosition(uv, z);
    vec3 N = rgGBufferNormalAt(p);
    int ci = rgCascadeAt(P);
    const vec3 palette[5] = vec3[5](vec3(0.9, 0.25, 0.2), vec3(0.25, 0.8, 0.25), vec3(0.25, 0.45, 0.95), vec3(0.95, 0.85, 0.2), vec3(0.5));
    float lit = rgCascades.c.info.x > 0.0 ? rgSunShadow(P, N) : 1.0;
    color = vec4(palette[min(ci, 4)] * (0.3 + 0.7 * lit), 1.0);
}

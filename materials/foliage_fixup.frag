#version 460
// The G-buffer fix-up of foliage (seed 000 lst:3): read what the foliage pass wrote (GB0, GB1),
// fill GB2 and GB3 with global values — no metal, the foliage reflectance, AO 1 — and the
// radiosity of a uniform sky of illuminance foliage_ambient on a diffuse surface (E·ρ/π, in nits).
// Runs on the foliage stencil class only.
#include "gbuffer_disney.glsl"

layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 gb2;
layout(location = 1) out vec4 gb3;
layout(set = 0, binding = 0) uniform sampler2D GB0;
layout(set = 0, binding = 1) uniform sampler2D GB1;
layout(set = 0, binding = 2) uniform Params { float foliage_reflectance; float foliage_ambient; } params;

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    // GB2 and GB3 are not read: unpack needs four texels, but only GB0 and GB1's fields are used.
    GBuffer_disney g = unpackGBuffer_disney(texelFetch(GB0, p, 0), texelFetch(GB1, p, 0), vec4(0.0), vec4(0.0));
    g.reserved = 0.0;
    g.metalMask = 0.0;
    g.reflectance = params.foliage_reflectance;
    g.ao = 1.0;
    g.emissive = g.baseColor * params.foliage_ambient / 3.14159265358979;
    vec4 t0, t1;
    packGBuffer_disney(g, t0, t1, gb2, gb3);
}

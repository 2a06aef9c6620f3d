#version 460
// The G-buffer fix-up of foliage (seed 000 lst:3): read what the foliage pass wrote (GB0, GB1),
// fill GB2 and GB3 with global values — no metal, the foliage reflectance, AO 1 — and, as lst:3
// does, the radiosity of the distant diffuse probe at the normal: the environment's SH irradiance
// on the leaf's diffuse colour, E(n)·ρ/π in nits. GB2's reserved channel says so (1: GB3 holds
// radiosity): the standard lighting then adds no second probe diffuse and occludes the radiosity
// by the AO as it would the probe's (materials/standard_shading.glsl). Runs on the foliage stencil
// class only.
#include "lib/environment.glsl"
#include "gbuffer_disney.glsl"

layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 gb2;
layout(location = 1) out vec4 gb3;
layout(set = 0, binding = 0) uniform sampler2D GB0;
layout(set = 0, binding = 1) uniform sampler2D GB1;
layout(set = 0, binding = 2) uniform Params { float foliage_reflectance; } params;
layout(set = 0, binding = 3, std140) uniform env_sh { vec4 coefficients[9]; } sh;

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    // GB2 and GB3 are not read: unpack needs four texels, but only GB0 and GB1's fields are used.
    GBuffer_disney g = unpackGBuffer_disney(texelFetch(GB0, p, 0), texelFetch(GB1, p, 0), vec4(0.0), vec4(0.0));
    g.reserved = 1.0;  // GB3 holds radiosity
    g.metalMask = 0.0;
    g.reflectance = params.foliage_reflectance;
    g.ao = 1.0;
    g.emissive = g.baseColor * rgShIrradiance(sh.coefficients, g.normal) / RG_PI;
    vec4 t0, t1;
    packGBuffer_disney(g, t0, t1, gb2, gb3);
}

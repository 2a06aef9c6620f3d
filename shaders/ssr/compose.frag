#version 460
// IBL composition (seed 002 §4.9.5) for the standard lighting path: the lighting passes added the
// distant probe's specular; here the short-range reflection replaces it where SSR found one —
//   RGB = SSR.rgb · SSR.a + distant probe · (1 − SSR.a)
// — by adding SSR.a · (SSR.rgb − probe) through the same split-sum weight (f0 DFG.x + f90 DFG.y)
// and specular occlusion (additive blend into the HDR). Local probes go between the two once they
// exist. Stencil-tested to the standard class (the layout it decodes).
#define RG_IBL 1
#include "lib/scene.glsl"
#include "lib/brdf.glsl"
#include "lib/ibl.glsl"
#include "lib/exposure.glsl"
#include "gbuffer_disney.glsl"

layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 color;
layout(set = 0, binding = 0) uniform sampler2D GB0;
layout(set = 0, binding = 1) uniform sampler2D GB1;
layout(set = 0, binding = 2) uniform sampler2D GB2;
layout(set = 0, binding = 3) uniform sampler2D depth;
layout(set = 0, binding = 4) uniform sampler2D ssr;
layout(set = 0, binding = 5, std430) readonly buffer exposure { RgExposureState state; } ex;
layout(set = 0, binding = 6) uniform Params { float initial_ev100; } params;

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec4 reflection = texelFetch(ssr, p, 0);
    color = vec4(0.0);
    if (reflection.a <= 0.0) return;
    GBuffer_disney g = unpackGBuffer_disney(texelFetch(GB0, p, 0), texelFetch(GB1, p, 0), texelFetch(GB2, p, 0), vec4(0.0));
    vec3 position = rgWorldPosition(uv, texelFetch(depth, p, 0).r);
    vec3 V = normalize(camera.position.xyz - position);
    vec3 N = g.normal;
    vec3 f0 = mix(vec3(rgDielectricF0(g.reflectance)), g.baseColor, g.metalMask);
    float f90 = clamp(50.0 * dot(f0, vec3(0.33)), 0.0, 1.0);
    float linearRoughness = 1.0 - g.smoothness;
    float alpha = linearRoughness * linearRoughness;
    float NdotV = max(dot(N, V), 0.5 / RG_DFG_SIZE);
    vec3 dfgTerms = rgDfg(NdotV, linearRoughness);
    float mips = float(textureQueryLevels(env_specular));
    vec3 Rd = rgSpecularDominantDir(N, reflect(-V, N), alpha);
    float pre = rgPreExposure(ex.state, params.initial_ev100);
    vec3 probe = textureLod(env_specular, Rd, sqrt(linearRoughness) * (mips - 1.0)).rgb * pre;
    float occlusion = rgSpecularOcclusion(max(dot(N, V), 0.0), rgAmbientOcclusion(g.ao), alpha);
    color = vec4(reflection.a * (reflection.rgb - probe) * (f0 * dfgTerms.x + f90 * dfgTerms.y) * occlusion, 0.0);
}

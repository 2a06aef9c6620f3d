#version 460
// Debug views of the disney G-buffer, display-ready (sRGB-encoded, in 0..1):
// 0 normals (world, 0.5 + 0.5·n), 1 base colour, 2 smoothness, 3 metal mask, 4 materialId (a
// distinct colour per id), 5 reflectance, 6 ambient occlusion, 7 emissive (log-scaled nits).
// With RG_TWO_COLOUR_ID (the pipeline has the two-colour material), its pixels show their diffuse
// colour as the base colour, their f0 colour as the reflectance and no metal mask.
#include "lib/photometry.glsl"
#include "gbuffer_disney.glsl"
#ifdef RG_TWO_COLOUR_ID
#include "gbuffer_two_colour.glsl"
#endif

layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 color;
layout(set = 0, binding = 0) uniform sampler2D GB0;
layout(set = 0, binding = 1) uniform sampler2D GB1;
layout(set = 0, binding = 2) uniform sampler2D GB2;
layout(set = 0, binding = 3) uniform sampler2D GB3;
layout(set = 0, binding = 4) uniform sampler2D depth;
layout(set = 0, binding = 5) uniform Params { float view; } params;

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    if (texelFetch(depth, p, 0).r >= 1.0) { color = vec4(0.0, 0.0, 0.0, 1.0); return; }
    GBuffer_disney g = unpackGBuffer_disney(texelFetch(GB0, p, 0), texelFetch(GB1, p, 0), texelFetch(GB2, p, 0),
                                            texelFetch(GB3, p, 0));
    int v = int(params.view + 0.5);
    vec3 c;
    if (v == 0) c = g.normal * 0.5 + 0.5;                       // already a display value
    else if (v == 1) c = rgLinearToSrgb(g.baseColor);
    else if (v == 2) c = vec3(g.smoothness);
    else if (v == 3) c = vec3(g.metalMask);
    else if (v == 4) {
        const vec3 palette[4] = vec3[](vec3(0.9, 0.9, 0.9), vec3(0.9, 0.2, 0.2), vec3(0.2, 0.8, 0.2), vec3(0.2, 0.4, 0.9));
        c = palette[g.materialId & 3u];
    } else if (v == 5) c = vec3(g.reflectance);
    else if (v == 6) c = vec3(g.ao);
    else c = vec3(clamp(log2(1.0 + rgLuminance(g.emissive)) / 16.0, 0.0, 1.0));
#ifdef RG_TWO_COLOUR_ID
    if (g.materialId == uint(RG_TWO_COLOUR_ID)) {
        GBuffer_two_colour t = unpackGBuffer_two_colour(texelFetch(GB0, p, 0), texelFetch(GB1, p, 0), texelFetch(GB2, p, 0),
                                                        texelFetch(GB3, p, 0));
        if (v == 1) c = rgLinearToSrgb(t.diffuseColor);
        else if (v == 3) c = vec3(0.0);
        else if (v == 5) c = rgLinearToSrgb(t.f0);
    }
#endif
    color = vec4(c, 1.0);
}

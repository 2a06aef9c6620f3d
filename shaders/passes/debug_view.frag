#version 460
// Debug views of the G-buffer, display-ready (sRGB-encoded, in 0..1), each pixel decoded with its
// own material's layout (gbuffer_pipeline.glsl, generated: RgGBufferView by the stencil's material identity):
// 0 normals (world, 0.5 + 0.5·n), 1 base colour, 2 smoothness, 3 metal mask, 4 the material identity (a
// distinct colour per material: its stencil value), 5 reflectance (a layout's f0 colour where it keeps one), 6 ambient
// occlusion, 7 emissive (log-scaled nits), 8 the baked lightmap (the G-buffer pass wrote it as the
// emission with RG_LIGHTMAP_VIEW: lux or nits, in colour, x / (1 + x) of x = value / 300). A parameter the pixel's layout does not hold shows as
// magenta-and-black stripes, so it is not mistaken for a value.
#include "lib/photometry.glsl"
#include "gbuffer_pipeline.glsl"

layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 color;
layout(set = 0, binding = 0) uniform sampler2D GB0;
layout(set = 0, binding = 1) uniform sampler2D GB1;
layout(set = 0, binding = 2) uniform sampler2D GB2;
layout(set = 0, binding = 3) uniform sampler2D GB3;
layout(set = 0, binding = 4) uniform sampler2D depth;
layout(set = 0, binding = 6) uniform usampler2D depth_stencil;
layout(set = 0, binding = 5) uniform Params { float view; } params;

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    if (texelFetch(depth, p, 0).r >= 1.0) { color = vec4(0.0, 0.0, 0.0, 1.0); return; }
    RgGBufferView g = rgGBufferAt(p);
    int v = int(params.view + 0.5);
    const uint needs[8] = uint[](RG_VIEW_NORMAL, RG_VIEW_BASE_COLOR, RG_VIEW_SMOOTHNESS, RG_VIEW_METAL_MASK, 0u,
                                 RG_VIEW_REFLECTANCE | RG_VIEW_F0, RG_VIEW_AO, RG_VIEW_EMISSIVE);
    vec3 c;
    if (v == 0) c = g.normal * 0.5 + 0.5;                       // already a display value
    else if (v == 1) c = rgLinearToSrgb(g.baseColor);
    else if (v == 2) c = vec3(g.smoothness);
    else if (v == 3) c = vec3(g.metalMask);
    else if (v == 4) {
        float hue = fract(float(g.identity) * 0.618034);  // golden-ratio hues: neighbours differ
        c = clamp(abs(mod(hue * 6.0 + vec3(0.0, 4.0, 2.0), 6.0) - 3.0) - 1.0, 0.0, 1.0) * 0.75 + 0.15;
    } else if (v == 5) c = (g.has & RG_VIEW_F0) != 0u ? rgLinearToSrgb(g.f0) : vec3(g.reflectance);
    else if (v == 6) c = vec3(g.ao);
    else if (v == 7) c = vec3(clamp(log2(1.0 + rgLuminance(g.emissive)) / 16.0, 0.0, 1.0));
    else {
        vec3 x = max(g.emissive, vec3(0.0)) / 300.0;
        c = rgLinearToSrgb(x / (1.0 + x));
    }
    if (v != 4 && (g.has & needs[clamp(v == 8 ? 7 : v, 0, 7)]) == 0u)
        c = ((p.x + p.y) / 4) % 2 == 0 ? vec3(1.0, 0.0, 1.0) : vec3(0.0);
    color = vec4(c, 1.0);
}

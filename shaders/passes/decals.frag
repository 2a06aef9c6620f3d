#version 460
// Deferred decals (seed 000 §3.3): every scene decal whose box encloses the pixel's surface
// blends the standard parameters with linear alpha blending, in decoded form (no programmable
// blending here: the pass reads copies of the targets and re-packs). Each pixel is decoded and
// re-packed with its own material's layout (gbuffer_pipeline.glsl, generated from the pipeline's
// materials: RgGBufferView by the pixel's stencil value, its material identity) and only the parameters its material lets decals blend
// (rg.material's `decals`: by default the common Normal, BaseColor and Smoothness; MetalMask and
// Reflectance on the standard material) change; MaterialId, MaterialData and a layout's own
// channels are never blended. Pixels no decal touches keep the G-buffer as it is (discard).
#define RG_WITH_DECALS
#include "lib/scene.glsl"
#include "gbuffer_pipeline.glsl"
#if (RG_DECAL_TARGETS & 8) != 0
#error a material lets decals blend a channel in the fourth target (GB3), which the decal pass does not write: keep decal channels in GB0, GB1 or GB2, or leave them out of the material decals
#endif

layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 gb0;
layout(location = 1) out vec4 gb1;
layout(location = 2) out vec4 gb2;
layout(set = 0, binding = 0) uniform sampler2D GB0_in;
layout(set = 0, binding = 1) uniform sampler2D GB1_in;
layout(set = 0, binding = 2) uniform sampler2D GB2_in;
layout(set = 0, binding = 3) uniform sampler2D depth;
layout(set = 0, binding = 4) uniform usampler2D depth_stencil;  // the material identity

void main() {
    if (decals.count.x == 0u) discard;  // a scene without decals pays for one load per pixel
    ivec2 p = ivec2(gl_FragCoord.xy);
    float d = texelFetch(depth, p, 0).r;
    if (d >= 1.0) discard;
    vec4 t0 = texelFetch(GB0_in, p, 0), t1 = texelFetch(GB1_in, p, 0), t2 = texelFetch(GB2_in, p, 0);
    RgGBufferView g = rgDecodeGBuffer(texelFetch(depth_stencil, p, 0).r, t0, t1, t2, vec4(0.0));
    if (g.decals == 0u) discard;  // a material decals leave alone
    vec3 position = rgWorldPosition(uv, d);
    bool touched = false;
    for (uint i = 0u; i < decals.count.x; ++i) {
        RgDecal decal = decals.decal[i];
        vec3 q = (decal.worldToBox * vec4(position, 1.0)).xyz;
        if (any(greaterThan(abs(q), vec3(0.5)))) continue;
        float a = decal.baseColorOpacity.a;
        if (decal.flags.x > 0.5) g.baseColor = mix(g.baseColor, decal.baseColorOpacity.rgb, a);
        if (decal.flags.y > 0.5) g.smoothness = mix(g.smoothness, decal.params.x, a);
        if (decal.flags.z > 0.5) g.metalMask = mix(g.metalMask, decal.params.y, a);
        if (decal.flags.w > 0.5) g.reflectance = mix(g.reflectance, decal.params.z, a);
        if (decal.axis.w > 0.5) g.normal = normalize(mix(g.normal, decal.axis.xyz, a));
        touched = true;
    }
    if (!touched) discard;
    vec4 o3;
    rgEncodeDecals(g, t0, t1, t2, vec4(0.0), gb0, gb1, gb2, o3);  // only the material's decal parameters are written back
}

#version 460
// Packs deterministic per-pixel values into the four targets of the default 'disney' G-buffer
// layout with the generated packGBuffer_disney. test_layout_gpu.cpp writes the generated code
// as gbuffer_disney.glsl next to a copy of this file, computes the same values in C++, unpacks
// the read-back targets with rg::unpackTexel and compares.
#include "gbuffer_disney.glsl"
#include "test/layout/hash.glsl"

layout(location = 0) out vec4 GB0;
layout(location = 1) out vec4 GB1;
layout(location = 2) out vec4 GB2;
layout(location = 3) out vec4 GB3;

void main() {
    uvec2 p = uvec2(gl_FragCoord.xy);
    // Channel numbers are the indices of LayoutInfo::channels.
    GBuffer_disney g;
    g.normal = rg_testDirection(p, 0u);
    g.smoothness = rg_testUnorm(p, 1u, 0u);
    g.materialId = rg_testUint(p, 2u, 0u, 2u);
    g.baseColor = rg_testColour(p, 3u);
    g.materialData = rg_testUint(p, 4u, 0u, 5u);
    g.normalExtra = rg_testUint(p, 5u, 0u, 3u);
    g.reserved = rg_testUnorm(p, 6u, 0u);
    g.metalMask = rg_testUnorm(p, 7u, 0u);
    g.reflectance = rg_testUnorm(p, 8u, 0u);
    g.ao = rg_testUnorm(p, 9u, 0u);
    g.emissive = vec3(rg_testFloat(p, 10u, 0u), rg_testFloat(p, 10u, 1u), rg_testFloat(p, 10u, 2u));
    packGBuffer_disney(g, GB0, GB1, GB2, GB3);
}

#version 460
// Writes one material into the four targets of the `disney` layout through the pack function
// rgraph generated from materials/disney.lua: the G-buffer pass's job, without the scene.
#include "gbuffer_disney.glsl"

layout(location = 0) out vec4 gb0;
layout(location = 1) out vec4 gb1;
layout(location = 2) out vec4 gb2;
layout(location = 3) out vec4 gb3;
layout(set = 0, binding = 0) uniform Params {
    vec4 normal;
    vec4 baseColor;
    float smoothness;
    float metalMask;
    float reflectance;
    float ao;
    float materialId;
} params;

void main() {
    GBuffer_disney g;
    g.normal = normalize(params.normal.xyz);
    g.smoothness = params.smoothness;
    g.materialId = uint(params.materialId);
    g.baseColor = params.baseColor.rgb;
    g.materialData = 0u;
    g.normalExtra = 0u;
    g.reserved = 0.0;
    g.metalMask = params.metalMask;
    g.reflectance = params.reflectance;
    g.ao = params.ao;
    g.emissive = vec3(0.0);
    packGBuffer_disney(g, gb0, gb1, gb2, gb3);
}

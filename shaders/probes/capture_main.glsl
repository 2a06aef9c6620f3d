// The body of the local light probe capture (probes/capture.frag), shared with the capture shaders
// rgraph generates per pipeline material: those define RG_CAPTURE_MATERIAL and
// rgCaptureSurface(), which runs the material's own surface function and reads the standard
// parameters from its layout (the material's `channels`), so a team's material is captured as it
// decodes, not as the standard material.
// Local light probe capture, shading (seed 002 §4.9.1.2): "specular is ignored during the
// capture; metallic surfaces are approximated as diffuse with f0 as albedo; visibility is stored
// in alpha". The surface of each draw's material (lib/material.glsl's factors and textures), lit
// by every light of the scene with the Disney diffuse, each light's visibility from a shadow ray
// through the scene's triangles (lib/bvh.glsl: the capture runs once per scene, so exact shadows
// are affordable), plus the distant probe's diffuse (its SH through the DFG table's Disney
// diffuse term towards the probe, as lib/ibl.glsl lights the frame) times the material's AO, and
// emission. Absolute luminance (nits), alpha 1; where nothing is drawn the target stays (0, 0, 0, 0).
#include "lib/material.glsl"
#include "lib/environment.glsl"
#include "lib/lighting.glsl"
#include "lib/bvh.glsl"

layout(location = 0) in vec3 worldPosition;
layout(location = 1) in vec3 worldNormal;
layout(location = 2) in vec4 worldTangent;
layout(location = 3) in vec2 uv0;
layout(location = 4) in vec2 uv1;
layout(location = 5) flat in vec3 eye;
layout(location = 6) in vec4 vertexColor;
layout(location = 0) out vec4 color;
layout(set = 0, binding = 0, std140) uniform env_sh { vec4 coefficients[9]; } rgEnvSh;
layout(set = 0, binding = 1) uniform sampler2D dfg;

#ifndef RG_CAPTURE_MATERIAL
// Without a generated material prologue: the sampled surface as the standard material reads it.
void rgCaptureSurface(RgSurface s, out vec3 N, out vec3 albedo, out float linearRoughness, out float ao, out vec3 emissive) {
    vec3 f0 = mix(vec3(rgDielectricF0(s.reflectance)), s.baseColor, s.metalMask);
    N = s.normal;
    albedo = s.twoColour ? s.diffuseColor : mix(s.baseColor, f0, s.metalMask);
    linearRoughness = 1.0 - s.smoothness;
    ao = s.ao;
    emissive = s.emissive;
}
#endif

void main() {
    // The facing from the geometry: the capture's face projections do not keep one winding.
    vec3 V = normalize(eye - worldPosition);
    RgSurface s = rgSampleSurface(worldPosition, worldNormal, worldTangent, uv0, uv1, vertexColor, dot(worldNormal, V) >= 0.0);
#if RG_ALPHA_MASK
    if (s.opacity < material.factors2.z) discard;  // alpha mask (only this variant discards: passes/scene_pass.cpp variantKey)
#endif
    vec3 N, albedo, emissive;
    float linearRoughness, ao;
    rgCaptureSurface(s, N, albedo, linearRoughness, ao, emissive);
    vec3 luminance = emissive;
    vec3 origin = worldPosition + N * 2e-3;
    for (uint i = 0u; i < rgLightCount(); ++i) {
        RgLightSample l = rgEvaluateLightUnshadowed(i, worldPosition, N, V, linearRoughness);
        if (dot(l.diffuseIlluminance, vec3(1.0)) <= 0.0) continue;
        RgLight light = rgLight(i);
        float distance = rgLightType(light) == RG_LIGHT_SUN ? 1e5 : length(light.positionType.xyz - worldPosition) - 1e-2;
        if (rgOccluded(origin, l.Ld, distance)) continue;
        luminance += albedo * rgDiffuseBrdf(N, V, l.Ld, linearRoughness) * l.diffuseIlluminance;
    }
    float NdotV = clamp(dot(N, V), 0.5 / 128.0, 1.0);
    float disney = textureLod(dfg, clamp(vec2(NdotV, linearRoughness), vec2(0.5 / 128.0), vec2(1.0 - 0.5 / 128.0)), 0.0).z;
    luminance += albedo * rgShIrradiance(rgEnvSh.coefficients, N) / RG_PI * disney * ao;
    color = vec4(luminance, 1.0);
}

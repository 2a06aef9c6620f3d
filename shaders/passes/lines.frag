#version 460
// The scene's points and lines, unlit as glTF viewers draw them: the material's base colour
// (× its texture, × COLOR_0) shown as glTF's emissive is — relative to the exposure at
// RG_BASE_COLOR_EC stops (graph/scene/scene.h kGltfEmissiveEc: a factor of 1 white before the
// tone curve) — plus the material's own emission, written pre-exposed with its opacity.
#include "lib/scene.glsl"
#include "lib/material.glsl"
#include "lib/exposure.glsl"

#ifndef RG_BASE_COLOR_EC
#define RG_BASE_COLOR_EC 0.0
#endif

layout(location = 0) in vec2 uv0;
layout(location = 1) in vec2 uv1;
layout(location = 2) in vec4 vertexColor;
layout(location = 0) out vec4 color;

layout(set = 0, binding = 0, std140) uniform exposure { RgExposureState state; } ex;
layout(set = 0, binding = 1) uniform Params { float initial_ev100; } params;

void main() {
    vec4 base = rgSampleMaterialTexture(baseColorTex, 1, 0, uv0, uv1, vec4(1.0)) * vertexColor;
    float opacity = material.baseColorOpacity.a * base.a;
#if RG_ALPHA_MASK
    if (opacity < material.factors2.z) discard;  // alpha mask
#endif
    // Emission: nits, or (emissive.w = 1) relative to the exposure like the base colour.
    float scale = rgEmissiveScale(ex.state, params.initial_ev100);
    vec3 emissive = material.emissive.rgb * rgSampleMaterialTexture(emissiveTex, 16, 4, uv0, uv1, vec4(1.0)).rgb *
                    mix(1.0, scale, material.emissive.w);
    vec3 luminance = material.baseColorOpacity.rgb * base.rgb * (scale * exp2(float(RG_BASE_COLOR_EC))) + emissive;
    color = vec4(luminance * rgPreExposure(ex.state, params.initial_ev100), opacity);
}

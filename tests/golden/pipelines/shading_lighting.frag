#version 460
// Deferred lighting of the analytic scene: Lambert diffuse plus GGX specular (height-correlated
// Smith, Schlick Fresnel) under the sun with a sphere shadow on the ground, a hemispherical sky
// ambient term, and the sky itself where nothing was hit. Radiance in HDR (highlights above 1).
#include "shading_common.glsl"

layout(location = 0) out vec4 hdr;
layout(set = 0, binding = 0) uniform sampler2D normal;
layout(set = 0, binding = 1) uniform sampler2D albedo;
layout(set = 0, binding = 2) uniform usampler2D material;
layout(set = 0, binding = 3) uniform Params { float jitter; float sun_elevation; float sun_intensity; } params;
layout(push_constant) uniform Constants { vec2 rg_outputSize; float rg_frame; } pc;

float ggx(float NoH, float a) {
    float a2 = a * a;
    float f = NoH * NoH * (a2 - 1.0) + 1.0;
    return a2 / (kPi * f * f);
}

float smithVisibility(float NoV, float NoL, float a) {
    float a2 = a * a;
    float v = NoL * sqrt(NoV * NoV * (1.0 - a2) + a2);
    float l = NoV * sqrt(NoL * NoL * (1.0 - a2) + a2);
    return 0.5 / (v + l);
}

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec3 d = cameraRay(gl_FragCoord.xy + jitterOffset(pc.rg_frame, params.jitter), pc.rg_outputSize);
    uint id = texelFetch(material, p, 0).r;
    if (id == 0u) {
        hdr = vec4(sky(d), 1.0);
        return;
    }
    vec4 nt = texelFetch(normal, p, 0);
    vec3 n = normalize(nt.xyz);
    vec3 base = texelFetch(albedo, p, 0).rgb;
    vec3 pos = kEye + nt.w * d;
    vec3 l = sunDirection(params.sun_elevation);
    vec3 v = -d;
    vec3 h = normalize(l + v);
    float NoL = clamp(dot(n, l), 0.0, 1.0), NoV = clamp(dot(n, v), 1e-4, 1.0), NoH = clamp(dot(n, h), 0.0, 1.0);
    float roughness = id == 1u ? 0.3 : 0.75;
    float a = roughness * roughness;
    float f = 0.04 + 0.96 * pow(1.0 - clamp(dot(v, h), 0.0, 1.0), 5.0);
    float shadow = id == 2u && hitSphere(pos + 1e-3 * n, l) > 0.0 ? 0.0 : 1.0;
    vec3 sun = vec3(1.0, 0.96, 0.9) * params.sun_intensity;
    vec3 direct = (base * (1.0 - f) / kPi + vec3(ggx(NoH, a) * smithVisibility(NoV, NoL, a) * f)) * sun * NoL * shadow;
    vec3 ambient = base * sky(n) * (0.5 + 0.5 * n.y) * 0.6;
    hdr = vec4(direct + ambient, 1.0);
}

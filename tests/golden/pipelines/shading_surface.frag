#version 460
// G-buffer of the analytic scene: world normal and hit distance, sRGB albedo, material id.
#include "shading_common.glsl"

layout(location = 0) out vec4 normalOut;
layout(location = 1) out vec4 albedoOut;
layout(location = 2) out uint materialOut;
layout(set = 0, binding = 0) uniform Params { float jitter; } params;
layout(push_constant) uniform Constants { vec2 rg_outputSize; float rg_frame; } pc;

void main() {
    vec2 pixel = gl_FragCoord.xy + jitterOffset(pc.rg_frame, params.jitter);
    vec3 d = cameraRay(pixel, pc.rg_outputSize);
    float ts = hitSphere(kEye, d), tg = hitGround(kEye, d);
    if (ts > 0.0) {
        vec3 n = normalize(kEye + ts * d - kSphereCentre);
        normalOut = vec4(n, ts);
        albedoOut = vec4(0.85, 0.35, 0.12, 1.0);
        materialOut = 1u;
    } else if (tg > 0.0) {
        vec3 p = kEye + tg * d;
        float checker = mod(floor(p.x * 2.0) + floor(p.z * 2.0), 2.0);
        normalOut = vec4(0.0, 1.0, 0.0, tg);
        albedoOut = vec4(vec3(mix(0.25, 0.75, checker)), 1.0);
        materialOut = 2u;
    } else {
        normalOut = vec4(0.0);
        albedoOut = vec4(0.0);
        materialOut = 0u;
    }
}

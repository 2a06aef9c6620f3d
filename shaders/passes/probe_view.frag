#version 460
// The `probes` debug view: which local light probe reflects each pixel (lib/probes.glsl), in the
// composition's order and weights (lib/ibl.glsl rgComposeReflection, §4.9.5) as if every capture
// saw something in every direction and SSR found nothing: probe k in colour k of the palette
// below, times its weight a = saturate(influence − Alpha); the distant probe, for the rest, grey.
// Pixels without geometry stay black.
#include "lib/scene.glsl"
#include "lib/probes.glsl"

layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 color;
layout(set = 0, binding = 0) uniform sampler2D depth;

const vec3 kPalette[RG_MAX_PROBES] = vec3[](vec3(0.9, 0.2, 0.2), vec3(0.2, 0.8, 0.2), vec3(0.25, 0.4, 0.95), vec3(0.95, 0.85, 0.2),
                                            vec3(0.85, 0.3, 0.9), vec3(0.2, 0.85, 0.9), vec3(0.95, 0.55, 0.15), vec3(1.0, 1.0, 1.0));
const vec3 kDistant = vec3(0.18);

void main() {
    float z = texelFetch(depth, ivec2(gl_FragCoord.xy), 0).r;
    color = vec4(0.0, 0.0, 0.0, 1.0);
    if (z >= 1.0) return;
    vec3 P = rgWorldPosition(uv, z);
    vec3 rgb = vec3(0.0);
    float alpha = 0.0;
    for (uint k = 0u; k < rgProbes.count.x && alpha < 1.0; ++k) {
        float a = clamp(rgProbeInfluence(rgProbes.probe[k], P) - alpha, 0.0, 1.0);
        rgb += kPalette[k] * a;
        alpha = clamp(alpha + a, 0.0, 1.0);
    }
    color = vec4(rgb + kDistant * (1.0 - alpha), 1.0);
}

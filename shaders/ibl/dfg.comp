#version 460
// The pre-integrated DFG table (seed 002 §4.9.2–4.9.3, 128×128): texel (i, j) holds, for
// N·V = (i + ½)/128 and linear roughness (j + ½)/128 (α = linear roughness²),
//   x = ∫ Gv (1 − Fc),  y = ∫ Gv Fc   — the split-sum specular: LD · (f0 x + f90 y);
//   z = the renormalised Disney diffuse (lst:1) averaged over the cosine lobe — the diffuse: LD · z;
//   w = the sheen lobe's directional albedo E = ∫ D_Charlie V_Neubelt ⟨n·l⟩ for a sheen roughness of
//       (j + ½)/128 (lib/brdf.glsl; a white sheen colour): the sheen material scales its base by
//       1 − max(sheen colour) · E (materials/sheen_shading.glsl). It exceeds 1 at grazing views of
//       the smoothest sheens (Neubelt's visibility is not energy conserving there).
// With Gv = V_SmithGGXCorrelated · 4 (N·L)(V·H)/(N·H) for GGX-sampled half vectors, Fc = (1 − V·H)^5.
// graph/lighting's integrateDfg is its C++ twin.
#include "lib/brdf.glsl"
#include "lib/sampling.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 0, rgba16f) uniform writeonly image2D dfg;

const uint kSamples = 1024u;

vec2 hammersley(uint i, uint n) { return vec2((float(i) + 0.5) / float(n), float(bitfieldReverse(i)) * 2.3283064365386963e-10); }

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(dfg);
    if (any(greaterThanEqual(p, size))) return;
    float NdotV = (float(p.x) + 0.5) / float(size.x);
    float linearRoughness = (float(p.y) + 0.5) / float(size.y);
    float alpha = linearRoughness * linearRoughness;
    vec3 V = vec3(sqrt(1.0 - NdotV * NdotV), 0.0, NdotV);
    vec3 r = vec3(0.0);
    float sheen = 0.0;
    for (uint i = 0u; i < kSamples; ++i) {
        vec2 u = hammersley(i, kSamples);
        float phi = 2.0 * RG_PI * u.x;
        // Specular: GGX half vectors.
        float cosTheta = sqrt((1.0 - u.y) / (1.0 + (alpha * alpha - 1.0) * u.y));
        float sinTheta = sqrt(max(0.0, 1.0 - cosTheta * cosTheta));
        vec3 H = vec3(sinTheta * cos(phi), sinTheta * sin(phi), cosTheta);
        float VdotH = dot(V, H);
        vec3 L = 2.0 * VdotH * H - V;
        float NdotL = L.z, NdotH = H.z;
        if (NdotL > 0.0 && VdotH > 0.0) {
            float Gv = V_SmithGGXCorrelated(NdotL, NdotV, alpha) * 4.0 * NdotL * VdotH / NdotH;
            float Fc = rgPow5(1.0 - VdotH);
            r.x += Gv * (1.0 - Fc);
            r.y += Gv * Fc;
        }
        // Diffuse: cosine-distributed light directions, Fd without its 1/π (pdf cos/π cancels it).
        vec3 Ld = rgSampleCosineHemisphere(vec2(u.y, u.x));
        float LdotH = clamp(dot(Ld, normalize(V + Ld)), 0.0, 1.0);
        r.z += Fr_DisneyDiffuse(NdotV, Ld.z, LdotH, linearRoughness);
        // Sheen over the same cosine-distributed directions: f ⟨n·l⟩ / pdf = π D V.
        sheen += RG_PI * D_Charlie(normalize(V + Ld).z, rgSheenAlpha(linearRoughness)) * V_Neubelt(Ld.z, NdotV);
    }
    imageStore(dfg, p, vec4(r, sheen) / float(kSamples));
}

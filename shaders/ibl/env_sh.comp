#version 460
// Environment filtering, step 3 (seed 002 §4.9.2, the diffuse LD term): the radiance projected on
// order-2 spherical harmonics (9 RGB coefficients), read from the 32×32 level of the source cube
// with each texel's exact solid angle. The lighting takes irradiance from it (rgShIrradiance) and
// multiplies by the Disney diffuse term of the DFG table, so the diffuse is the renormalised Disney
// diffuse's, not Lambert's. One work group of 64 invocations, each summing a share of the texels.
#include "lib/environment.glsl"

layout(local_size_x = 64) in;
layout(set = 0, binding = 0) uniform samplerCube env_source;
layout(set = 0, binding = 1, std430) writeonly buffer env_sh { vec4 coefficients[9]; } sh;

shared vec3 partial[64][9];

void main() {
    uint id = gl_LocalInvocationID.x;
    int levels = textureQueryLevels(env_source);
    int lod = max(0, min(levels - 1, int(log2(float(textureSize(env_source, 0).x))) - 5));
    float size = float(textureSize(env_source, lod).x);
    uint texels = uint(size * size) * 6u;
    vec3 acc[9];
    for (int k = 0; k < 9; ++k) acc[k] = vec3(0.0);
    for (uint i = id; i < texels; i += 64u) {
        uint face = i / uint(size * size), r = i % uint(size * size);
        vec2 uv = (vec2(float(r % uint(size)), float(r / uint(size))) + 0.5) / size;
        vec3 d = rgCubeDirection(face, uv);
        vec3 L = textureLod(env_source, d, float(lod)).rgb * rgCubeTexelSolidAngle(uv, size);
        float y[9];
        rgShBasis(d, y);
        for (int k = 0; k < 9; ++k) acc[k] += L * y[k];
    }
    for (int k = 0; k < 9; ++k) partial[id][k] = acc[k];
    barrier();
    if (id < 9u) {
        vec3 s = vec3(0.0);
        for (int j = 0; j < 64; ++j) s += partial[j][id];
        sh.coefficients[id] = vec4(s, 0.0);
    }
}

#version 460
// Environment filtering, step 1b: the environment's hot texels — a sun, a lamp — taken out of the
// cube the pre-filter samples (seed 002 §4.9.2). A texel of env_source (mip 0) brighter than
// RG_HOT_FACTOR × the environment's mean radiance (env_sh's constant term) goes, with its direction
// and exact solid angle, into `env_hot`, and is 0 in `env_smooth`; every other texel is copied.
// env_prefilter then importance-samples the smooth cube, whose mips no longer smear a source
// 10⁴× brighter than the sky into directions its GGX tail barely reaches, and adds the hot texels
// exactly: Σ L D(h) (n·l) Ω over them, over the same normalisation. Texels past the list's
// capacity stay in the smooth cube (as before, only less accurate).
// One work group: each invocation scans a contiguous run of texels twice — counting, then, at the
// offset the counts before it give, listing — so the list's order (and every sum over it) is the
// same in every run.
#include "lib/environment.glsl"

#ifndef RG_HOT_FACTOR
#define RG_HOT_FACTOR 20.0
#endif
#define RG_HOT_CAPACITY 4096u
#define RG_HOT_INVOCATIONS 256u

layout(local_size_x = 256) in;
layout(set = 0, binding = 0) uniform samplerCube env_source;
layout(set = 0, binding = 1, rgba16f) uniform writeonly image2DArray env_smooth;
layout(set = 0, binding = 2, std140) uniform env_sh { vec4 coefficients[9]; } sh;
layout(set = 0, binding = 3, std430) writeonly buffer env_hot {
    uint count;  // texels listed (at most RG_HOT_CAPACITY)
    uint pad0, pad1, pad2;
    vec4 texel[2 * RG_HOT_CAPACITY];  // per texel: direction and solid angle, then radiance
} hot;

shared uint counts[RG_HOT_INVOCATIONS];

void main() {
    uint id = gl_LocalInvocationID.x;
    int size = imageSize(env_smooth).x;
    uint perFace = uint(size * size), total = 6u * perFace;
    uint run = (total + RG_HOT_INVOCATIONS - 1u) / RG_HOT_INVOCATIONS;
    uint first = min(id * run, total), last = min(first + run, total);
    const vec3 lum = vec3(0.2126, 0.7152, 0.0722);
    float threshold = RG_HOT_FACTOR * max(dot(sh.coefficients[0].rgb, lum) * 0.282095, 0.0);  // L00 · Y00: the mean radiance
    uint mine = 0u;
    for (uint i = first; i < last; ++i) {
        uint face = i / perFace, r = i % perFace;
        vec3 d = rgCubeDirection(face, (vec2(float(r % uint(size)), float(r / uint(size))) + 0.5) / float(size));
        vec4 L = textureLod(env_source, d, 0.0);
        mine += uint(threshold > 0.0 && dot(L.rgb, lum) > threshold);
    }
    counts[id] = mine;
    barrier();
    uint offset = 0u;
    for (uint k = 0u; k < id; ++k) offset += counts[k];
    for (uint i = first; i < last; ++i) {
        uint face = i / perFace, r = i % perFace;
        ivec2 xy = ivec2(int(r % uint(size)), int(r / uint(size)));
        vec2 uv = (vec2(xy) + 0.5) / float(size);
        vec3 d = rgCubeDirection(face, uv);
        vec4 L = textureLod(env_source, d, 0.0);
        if (threshold > 0.0 && dot(L.rgb, lum) > threshold && offset < RG_HOT_CAPACITY) {
            hot.texel[2u * offset] = vec4(d, rgCubeTexelSolidAngle(uv, float(size)));
            hot.texel[2u * offset + 1u] = vec4(L.rgb, 0.0);
            ++offset;
            imageStore(env_smooth, ivec3(xy, int(face)), vec4(0.0, 0.0, 0.0, L.a));
        } else {
            imageStore(env_smooth, ivec3(xy, int(face)), L);
        }
    }
    if (id == RG_HOT_INVOCATIONS - 1u) hot.count = min(offset, RG_HOT_CAPACITY);
}

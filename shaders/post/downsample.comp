#version 460
// A mip chain from mip 0, as a compute pass (per_mip): each mip m ≥ 1 resampled from mip m − 1 at
// its texel centres with the linear filter — a 2×2 box where the size halves exactly — the same
// image vkCmdBlitImage with VK_FILTER_LINEAR gives. As a shader it is compiled once and then found
// in the driver's shader cache; lavapipe's blits build their own shaders anew in every process
// (~110 ms for the environment cube's chain at start-up). For once-per-scene chains: per frame its
// per-mip dispatches cost more than blits (the HDR history's chain stays a blit, scripts/ssr.lua).
// RG_LAYERED: a cube or an array (image2DArray, z over the layers). Bind the image as `target`.
// RG_CUBE (with RG_LAYERED): a cube's faces, whose texels are not equal in solid angle (a corner's
// is a fifth of a face centre's): each texel is its four children's mean weighted by their solid
// angles, so every mip holds the radiance the finer one does over the same directions. An
// unweighted box over-weighted what lies near the corners — a sun there by up to 5× in the
// coarse mips the pre-filter's tail samples read (tests/gpu/test_ibl.cpp, PrefilteredProbe…).
layout(local_size_x = 8, local_size_y = 8) in;
#ifdef RG_LAYERED
layout(set = 0, binding = 0, rgba16f) uniform image2DArray target;
layout(set = 0, binding = 1) uniform sampler2DArray target_previous;
#else
layout(set = 0, binding = 0, rgba16f) uniform image2D target;
layout(set = 0, binding = 1) uniform sampler2D target_previous;
#endif
layout(push_constant) uniform Constants { float rg_mip; } pc;
#ifdef RG_CUBE
#include "lib/environment.glsl"
#endif

void main() {
    if (pc.rg_mip < 0.5) return;  // mip 0 is the source
    ivec3 p = ivec3(gl_GlobalInvocationID);
    ivec2 size = imageSize(target).xy;
    if (any(greaterThanEqual(p.xy, size))) return;
    vec2 uv = (vec2(p.xy) + 0.5) / vec2(size);
#if defined(RG_LAYERED) && defined(RG_CUBE)
    float finer = float(textureSize(target_previous, 0).x);
    vec4 sum = vec4(0.0);
    float weight = 0.0;
    for (int k = 0; k < 4; ++k) {
        ivec2 c = p.xy * 2 + ivec2(k & 1, k >> 1);
        float w = rgCubeTexelSolidAngle((vec2(c) + 0.5) / finer, finer);
        sum += texelFetch(target_previous, ivec3(c, p.z), 0) * w;
        weight += w;
    }
    imageStore(target, p, sum / weight);
#elif defined(RG_LAYERED)
    imageStore(target, p, textureLod(target_previous, vec3(uv, float(p.z)), 0.0));
#else
    imageStore(target, p.xy, textureLod(target_previous, uv, 0.0));
#endif
}

#version 460
// Environment filtering, step 1 (seed 002 §4.9.2): the scene's equirectangular environment
// (nits) resampled into mip 0 of a cube map; a `mips` pass then builds the cube's chain, which the
// filtered importance sampling of env_prefilter.comp and env_sh.comp read.
#include "lib/environment.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 0) uniform sampler2D SceneEnvironment;
layout(set = 0, binding = 1, rgba16f) uniform writeonly image2DArray env_source;

void main() {
    ivec3 p = ivec3(gl_GlobalInvocationID);
    ivec2 size = imageSize(env_source).xy;
    if (any(greaterThanEqual(p.xy, size))) return;
    vec3 d = rgCubeDirection(uint(p.z), (vec2(p.xy) + 0.5) / vec2(size));
    // Several taps across the texel's footprint: the equirect is usually finer than the face.
    vec3 sum = vec3(0.0);
    for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 2; ++i) {
            vec2 uv = (vec2(p.xy) + vec2(0.25 + 0.5 * float(i), 0.25 + 0.5 * float(j))) / vec2(size);
            sum += textureLod(SceneEnvironment, rgEquirectUv(rgCubeDirection(uint(p.z), uv)), 0.0).rgb;
        }
    imageStore(env_source, p, vec4(min(sum * 0.25, vec3(65000.0)), 1.0));
}

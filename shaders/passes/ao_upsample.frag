#version 460
// The filtered half-resolution AO (ao_blur.frag) at full resolution, for the `ssao` view and
// captures: lib/upsample.glsl's depth-aware upsample, the one the lighting passes run on their
// pixels (lib/ibl.glsl's rgAmbientOcclusion) — the four half-resolution texels around the pixel,
// weighted bilinearly and by how close each one's view distance is to the pixel's.
#include "lib/scene.glsl"
#include "lib/upsample.glsl"

layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 color;
layout(set = 0, binding = 0) uniform sampler2D ao_filtered;
layout(set = 0, binding = 1) uniform sampler2D depth;

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    float z = texelFetch(depth, p, 0).r;
    color = vec4(z >= 1.0 ? 1.0 : rgUpsampleHalf(ao_filtered, p, rgViewDistance(z)));
}

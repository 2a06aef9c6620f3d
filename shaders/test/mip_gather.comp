#version 460
// Texel (0, 0) of mip x of `chain` into texel x of `output` (zeros past the chain).
layout(local_size_x = 8) in;
layout(set = 0, binding = 0) uniform sampler2D chain;
layout(set = 0, binding = 1, rgba32f) uniform writeonly image2D output_;

void main() {
    int x = int(gl_GlobalInvocationID.x);
    if (x >= imageSize(output_).x) return;
    imageStore(output_, ivec2(x, 0), x < textureQueryLevels(chain) ? texelFetch(chain, ivec2(0), x) : vec4(0.0));
}

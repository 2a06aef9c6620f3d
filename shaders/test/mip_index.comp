#version 460
// Writes (mip, mip count, mip width, mip height) into every texel of the mip it is bound to
// (the compute kind's per_mip: one dispatch per mip).
layout(local_size_x = 4, local_size_y = 4) in;
layout(set = 0, binding = 0, rgba32f) uniform writeonly image2D chain;
layout(push_constant) uniform Constants { float rg_mip; float rg_mipCount; } pc;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(chain);
    if (any(greaterThanEqual(p, size))) return;
    imageStore(chain, p, vec4(pc.rg_mip, pc.rg_mipCount, vec2(size)));
}

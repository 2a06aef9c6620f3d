#version 460
// The Hi-Z depth pyramid (seed 002 §4.9.4, Uludağ 2014): mip 0 the depth buffer, each further mip
// the nearest (minimum) depth of the texels it covers in the one before — read through
// `hiz_previous` (the compute kind's per-mip chain), 3 wide where the level before is odd so no
// texel is skipped. Ray marches skip a whole cell when the ray is in front of its nearest depth.
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 0) uniform sampler2D depth;
layout(set = 0, binding = 1, r32f) uniform image2D hiz;
layout(set = 0, binding = 2) uniform sampler2D hiz_previous;
layout(push_constant) uniform Constants { float rg_mip; } pc;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(hiz);
    if (any(greaterThanEqual(p, size))) return;
    float d;
    if (pc.rg_mip < 0.5) {
        d = texelFetch(depth, p, 0).r;
    } else {
        ivec2 prev = textureSize(hiz_previous, 0);
        ivec2 extra = ivec2(prev.x > 2 * size.x ? 2 : 1, prev.y > 2 * size.y ? 2 : 1);
        d = 1.0;
        for (int j = 0; j <= extra.y; ++j)
            for (int i = 0; i <= extra.x; ++i) d = min(d, texelFetch(hiz_previous, min(2 * p + ivec2(i, j), prev - 1), 0).r);
    }
    imageStore(hiz, p, vec4(d));
}

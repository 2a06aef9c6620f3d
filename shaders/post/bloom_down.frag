#version 460
// Bloom, down the chain: each level is the previous one at half size, filtered with 13 bilinear
// taps (a 4x4 box at the centre plus four overlapping corner boxes, weights summing to 1), so
// every level keeps the image's average: the chain conserves energy. The first level, from the
// full-resolution image (RG_BLOOM_BOX, scripts/post.lua), takes a 4×4 box instead: four bilinear
// taps, each exactly the mean of a 2×2 quad — the same average for 4 taps of a CPU rasteriser's
// filtered reads instead of 13 (bloom_down1 ~4.7 -> ~1.9 ms at 1280×720 on lavapipe); the
// wider filter of the smaller levels still smooths what it leaves.
layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 color;
layout(set = 0, binding = 0) uniform sampler2D source;

void main() {
    vec2 t = 1.0 / vec2(textureSize(source, 0));
#ifdef RG_BLOOM_BOX
    vec3 box = texture(source, uv + t * vec2(-1, -1)).rgb + texture(source, uv + t * vec2(1, -1)).rgb +
               texture(source, uv + t * vec2(-1, 1)).rgb + texture(source, uv + t * vec2(1, 1)).rgb;
    color = vec4(box * 0.25, 1.0);
#else
    vec3 a = texture(source, uv + t * vec2(-2, -2)).rgb, b = texture(source, uv + t * vec2(0, -2)).rgb;
    vec3 c = texture(source, uv + t * vec2(2, -2)).rgb, d = texture(source, uv + t * vec2(-1, -1)).rgb;
    vec3 e = texture(source, uv + t * vec2(1, -1)).rgb, f = texture(source, uv + t * vec2(-2, 0)).rgb;
    vec3 g = texture(source, uv).rgb, h = texture(source, uv + t * vec2(2, 0)).rgb;
    vec3 i = texture(source, uv + t * vec2(-1, 1)).rgb, j = texture(source, uv + t * vec2(1, 1)).rgb;
    vec3 k = texture(source, uv + t * vec2(-2, 2)).rgb, l = texture(source, uv + t * vec2(0, 2)).rgb;
    vec3 m = texture(source, uv + t * vec2(2, 2)).rgb;
    vec3 sum = (d + e + i + j) * 0.125 + (a + c + k + m) * 0.03125 + (b + f + h + l) * 0.0625 + g * 0.125;
    color = vec4(sum, 1.0);
#endif
}

#version 460
// Bloom, up the chain: this level = its downsampled image + the smaller level upsampled with a
// tent (weights summing to 1). The top level divided by the number of levels is the average of
// the blurs at every scale, which keeps the image's energy. The tent is four bilinear taps half a
// texel of the smaller level from the centre: along each axis the mean of two linear
// interpolations a texel apart, a tent convolved with a one-texel box — 4 filtered reads instead
// of 9 (a 3×3 tent of taps one texel apart; bloom_up1 ~3.5 -> ~1.5 ms at 1280×720 on lavapipe).
layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 color;
layout(set = 0, binding = 0) uniform sampler2D down;   // this level, downsampled
layout(set = 0, binding = 1) uniform sampler2D lower;  // the level below, already accumulated

void main() {
    vec2 t = 0.5 / vec2(textureSize(lower, 0));
    vec3 s = texture(lower, uv + t * vec2(-1, -1)).rgb + texture(lower, uv + t * vec2(1, -1)).rgb +
             texture(lower, uv + t * vec2(-1, 1)).rgb + texture(lower, uv + t * vec2(1, 1)).rgb;
    color = vec4(texture(down, uv).rgb + s * 0.25, 1.0);
}

#version 460
// Bloom, up the chain: this level = its downsampled image + the smaller level upsampled with a
// 3x3 tent (weights summing to 1). The top level divided by the number of levels is the
// average of the blurs at every scale, which keeps the image's energy.
layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 color;
layout(set = 0, binding = 0) uniform sampler2D down;   // this level, downsampled
layout(set = 0, binding = 1) uniform sampler2D lower;  // the level below, already accumulated

void main() {
    vec2 t = 1.0 / vec2(textureSize(lower, 0));
    vec3 s = texture(lower, uv + t * vec2(-1, -1)).rgb + texture(lower, uv + t * vec2(1, -1)).rgb +
             texture(lower, uv + t * vec2(-1, 1)).rgb + texture(lower, uv + t * vec2(1, 1)).rgb;
    s += 2.0 * (texture(lower, uv + t * vec2(0, -1)).rgb + texture(lower, uv + t * vec2(-1, 0)).rgb +
                texture(lower, uv + t * vec2(1, 0)).rgb + texture(lower, uv + t * vec2(0, 1)).rgb);
    s += 4.0 * texture(lower, uv).rgb;
    color = vec4(texture(down, uv).rgb + s / 16.0, 1.0);
}

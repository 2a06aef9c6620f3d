#version 460
// A team's post pass at one of post.chain's insertion points (scripts/post.lua's post.at): the
// image before it, `source`, times `post_scale` plus `post_offset`, texel for texel.
layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 color;
layout(set = 0, binding = 0) uniform sampler2D source;
layout(set = 0, binding = 1) uniform Params {
    float post_scale;
    float post_offset;
} params;

void main() {
    vec4 c = texelFetch(source, ivec2(gl_FragCoord.xy), 0);
    color = vec4(c.rgb * params.post_scale + params.post_offset, 1.0);
}

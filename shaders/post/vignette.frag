#version 460
// A team's post pass for post.at (scripts/post.lua): a lens vignette on the exposed image, before
// the tone curve, so that it darkens light rather than display values. The cos⁴ law of natural
// vignetting: a lens images an off-axis point at angle θ with cos⁴θ of the on-axis illuminance;
// θ follows from the position in the frame and `vignette_fov`, the vertical field of view in
// degrees (the camera's), and `vignette` blends it in (0 none, 1 the whole law).
layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 color;
layout(set = 0, binding = 0) uniform sampler2D source;
layout(set = 0, binding = 1) uniform Params {
    float vignette;
    float vignette_fov;
} params;

void main() {
    vec2 size = vec2(textureSize(source, 0));
    // The point on an image plane at distance 1: ±tan(fov / 2) vertically, the aspect horizontally.
    vec2 ndc = (gl_FragCoord.xy / size) * 2.0 - 1.0;
    vec2 plane = ndc * tan(radians(params.vignette_fov) * 0.5) * vec2(size.x / size.y, 1.0);
    float cos2 = 1.0 / (1.0 + dot(plane, plane));  // cos²θ = 1 / (1 + tan²θ)
    float falloff = mix(1.0, cos2 * cos2, params.vignette);
    color = vec4(texelFetch(source, ivec2(gl_FragCoord.xy), 0).rgb * falloff, 1.0);
}

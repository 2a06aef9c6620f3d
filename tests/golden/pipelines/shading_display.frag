#version 460
// HDR -> display: exposure (EV), the ACES filmic fit (Narkowicz 2015), the sRGB transfer
// function, and an optional 4x4 ordered dither of +-0.5 LSB before the 8-bit target.
layout(location = 0) out vec4 ldr;
layout(set = 0, binding = 0) uniform sampler2D hdr;
layout(set = 0, binding = 1) uniform Params { float exposure; float dither; } params;

const float kBayer[16] = float[16](0.0, 8.0, 2.0, 10.0, 12.0, 4.0, 14.0, 6.0, 3.0, 11.0, 1.0, 9.0, 15.0, 7.0, 13.0, 5.0);

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec3 c = texelFetch(hdr, p, 0).rgb * exp2(params.exposure);
    c = clamp(c * (2.51 * c + 0.03) / (c * (2.43 * c + 0.59) + 0.14), 0.0, 1.0);
    c = mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(0.0031308, c));
    if (params.dither > 0.5) c += (kBayer[(p.y & 3) * 4 + (p.x & 3)] + 0.5) / 16.0 / 255.0 - 0.5 / 255.0;
    ldr = vec4(c, 1.0);
}

#version 460
// Evaluates the GLSL sRGB transfer functions at the inputs the test gives (one per invocation),
// so the shader library can be held to the definition at its breakpoints.
#include "lib/photometry.glsl"

layout(local_size_x = 64) in;
layout(set = 0, binding = 0) uniform Params { vec4 x[16]; } params;
layout(set = 0, binding = 1, std430) writeonly buffer srgb_out { float encoded[64]; float decoded[64]; } outp;

void main() {
    uint i = gl_GlobalInvocationID.x;
    float v = params.x[i / 4u][i % 4u];
    outp.encoded[i] = rgLinearToSrgb(vec3(v)).r;
    outp.decoded[i] = rgSrgbToLinear(vec3(v)).r;
}

#version 460
// A samplerBuffer bound to none of the scene's: a texel buffer rgraph does not bind (GpuTest,
// TexelBufferOutsideTheSceneIsNamed).
layout(set = 0, binding = 0) uniform samplerBuffer lut;
layout(location = 0) out vec4 color;
void main() { color = texelFetch(lut, 0); }

#version 460
// Adds a constant colour (Params.tint) to what is already in the target: used with additive
// blending by the reconfiguration tests.
layout(location = 0) out vec4 color;
layout(set = 0, binding = 0) uniform Params { vec4 tint; } params;

void main() { color = params.tint; }

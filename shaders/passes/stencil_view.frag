#version 460
// One stencil class of the stencil debug view: its colour where the stencil test passed.
layout(location = 0) out vec4 color;
layout(set = 0, binding = 0) uniform Params { vec4 class_color; } params;
void main() { color = params.class_color; }

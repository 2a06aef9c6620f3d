#version 460
// Deliberately broken: the GPU tests check that the error names this file, line 7 and the pass.
layout(location = 0) out vec4 color;

void main() {
    vec4 c = vec4(1.0);
    color = c * undefinedThing;
}

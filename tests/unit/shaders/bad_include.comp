#version 460
layout(local_size_x = 1) in;
#include "lib/broken.glsl"

void main() { float v = brokenHelper(1.0); }

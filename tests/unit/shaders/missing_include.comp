#version 460
layout(local_size_x = 1) in;
#include "does_not_exist.glsl"

void main() {}

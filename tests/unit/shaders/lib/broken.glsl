// An include with an error on line 5.
#ifndef BROKEN_GLSL
#define BROKEN_GLSL

float brokenHelper(float x) { return x * undeclaredScale; }
#endif

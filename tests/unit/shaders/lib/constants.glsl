// Found through the including file's folder (lib/), not through a search root.
#ifndef CONSTANTS_GLSL
#define CONSTANTS_GLSL
const float kPi = 3.14159265;
#endif

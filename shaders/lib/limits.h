// Limits the C++ core and the shaders share: this file is included by both (GLSL: lib/scene.glsl,
// lib/shadows.glsl; C++: graph/lighting/light_table.h, passes/gpu_scene.h), so each number is
// written once. Plain preprocessor only.
#ifndef RG_LIMITS_H
#define RG_LIMITS_H

// The most lights a scene sends to the GPU: the Lights block's light array has a fixed size so that
// the IES profiles follow it in the same block; the light tiles' global list and ShadowViews'
// per-light table are sized by it too.
#define RG_MAX_LIGHTS 1024

// The most shadow views of local lights a frame can have (lib/shadows.glsl's ShadowViews block):
// a cube light takes six, a spot of outer angle ≤ 60° one.
#define RG_MAX_SHADOW_VIEWS 48

#endif

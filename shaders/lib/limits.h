// Limits the C++ core and the shaders share: this file is included by both (GLSL: lib/scene.glsl,
// lib/shadows.glsl; C++: graph/lighting/light_table.h, passes/gpu_scene.h), so each number is
// written once. Plain preprocessor only.
#ifndef RG_LIMITS_H
#define RG_LIMITS_H

// The most lights a scene may have: the light lists (lib/light_tiles.glsl) hold 16-bit light
// indices. The Lights block and ShadowViews' per-light table are sized by the scene's own count;
// the light tiles' global list (the lights that reach every pixel) by this.
#define RG_MAX_LIGHTS 65536

// The most shadow views of local lights a frame can have (lib/shadows.glsl's ShadowViews block):
// a cube light takes six, a spot of outer angle ≤ 60° one.
#define RG_MAX_SHADOW_VIEWS 48

// The vec4 words of one draw in the scene's SceneTransforms (passes/gpu_scene.h): its world
// matrix's four columns, the normal matrix's three (the first's w: the draw's material's index in
// its window of materials, uint bits, for lib/material.glsl), the lightmap rect, the last frame's
// world matrix's four (passes/scene.vert, shadows/shadow.vert).
#define RG_TRANSFORM_WORDS 12

#endif

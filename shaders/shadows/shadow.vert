#version 460
// Shadow-map draws (the `scene` kind with shadow = true): depth only, layer `draw.layer.x` of the
// map from the matrix of that cascade. With RG_SHADOW_INSTANCES (a pass whose culling pass wrote
// indirect commands, shaders/shadows/cascade_cull.comp) a draw with an all-zero world is a batch
// of casters, instance k the draw `sun_shadow_instances` lists at firstInstance + k, its transform
// the scene's.
#include "lib/shadows.glsl"

layout(location = 0) in vec3 inPosition;

layout(push_constant) uniform Draw {
    mat4 world;
    vec4 layer;  // x: the layer (cascade) being drawn
} draw;

layout(set = 0, binding = 0, std430) readonly buffer sun_cascades { RgCascades c; } cascades;
#ifdef RG_SHADOW_INSTANCES
layout(set = 0, binding = 1, std430) readonly buffer sun_shadow_instances { uint draw[]; } instances;
#ifndef RG_TRANSFORMS_BINDING
#define RG_TRANSFORMS_BINDING 34
#endif
layout(set = 0, binding = RG_TRANSFORMS_BINDING, std430) readonly buffer SceneTransforms { vec4 t[]; } sceneTransforms;
#endif

void main() {
    mat4 world = draw.world;
#ifdef RG_SHADOW_INSTANCES
    if (draw.world[3][3] == 0.0) {  // all-zero push constants: a batch
        uint base = uint(RG_TRANSFORM_WORDS) * instances.draw[gl_InstanceIndex];
        world = mat4(sceneTransforms.t[base], sceneTransforms.t[base + 1u], sceneTransforms.t[base + 2u], sceneTransforms.t[base + 3u]);
    }
#endif
    gl_Position = cascades.c.viewProj[int(draw.layer.x + 0.5)] * (world * vec4(inPosition, 1.0));
}

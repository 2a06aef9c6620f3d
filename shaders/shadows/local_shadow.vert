#version 460
// Shadow-map draws of the local lights (the `scene` kind with shadow = true, views = "lights"):
// depth only, layer `draw.layer.x` of the map from the matrix of that shadow view (lib/shadows.glsl
// ShadowViews, written each frame by the scene from the lights that cast shadows). With
// RG_SHADOW_INSTANCES (a pass whose culling pass wrote indirect commands, shaders/shadows/
// local_cull.comp) a draw with an all-zero world is a batch of casters, instance k the draw
// `local_shadow_instances` lists at firstInstance + k, its transform the scene's.
#define RG_SHADOW_VIEWS 1
#include "lib/scene.glsl"
#include "lib/shadows.glsl"

layout(location = 0) in vec3 inPosition;

layout(push_constant) uniform Draw {
    mat4 world;
    vec4 layer;  // x: the layer (shadow view) being drawn
} draw;

#ifdef RG_SHADOW_INSTANCES
layout(set = 0, binding = 1, std430) readonly buffer local_shadow_instances { uint draw[]; } instances;
#ifndef RG_TRANSFORMS_BINDING
#define RG_TRANSFORMS_BINDING 34
#endif
layout(set = RG_CAMERA_SET, binding = RG_TRANSFORMS_BINDING, std430) readonly buffer SceneTransforms { vec4 t[]; } sceneTransforms;
#endif

void main() {
    mat4 world = draw.world;
#ifdef RG_SHADOW_INSTANCES
    if (draw.world[3][3] == 0.0) {  // all-zero push constants: a batch
        uint base = uint(RG_TRANSFORM_WORDS) * instances.draw[gl_InstanceIndex];
        world = mat4(sceneTransforms.t[base], sceneTransforms.t[base + 1u], sceneTransforms.t[base + 2u], sceneTransforms.t[base + 3u]);
    }
#endif
    gl_Position = rgShadowViews.view[int(draw.layer.x + 0.5)].viewProj * (world * vec4(inPosition, 1.0));
}

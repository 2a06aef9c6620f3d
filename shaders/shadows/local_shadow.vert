#version 460
// Shadow-map draws of the local lights (the `scene` kind with shadow = true, views = "lights"):
// depth only, layer `draw.layer.x` of the map from the matrix of that shadow view (lib/shadows.glsl
// ShadowViews, written each frame by the scene from the lights that cast shadows).
#define RG_SHADOW_VIEWS 1
#include "lib/scene.glsl"
#include "lib/shadows.glsl"

layout(location = 0) in vec3 inPosition;

layout(push_constant) uniform Draw {
    mat4 world;
    vec4 layer;  // x: the layer (shadow view) being drawn
} draw;

void main() {
    gl_Position = rgShadowViews.view[int(draw.layer.x + 0.5)].viewProj * (draw.world * vec4(inPosition, 1.0));
}

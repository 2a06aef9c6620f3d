#version 460
// Shadow-map draws (the `scene` kind with shadow = true): depth only, layer `draw.layer.x` of the
// map from the matrix of that cascade.
#include "lib/shadows.glsl"

layout(location = 0) in vec3 inPosition;

layout(push_constant) uniform Draw {
    mat4 world;
    vec4 layer;  // x: the layer (cascade) being drawn
} draw;

layout(set = 0, binding = 0, std430) readonly buffer sun_cascades { RgCascades c; } cascades;

void main() {
    gl_Position = cascades.c.viewProj[int(draw.layer.x + 0.5)] * (draw.world * vec4(inPosition, 1.0));
}

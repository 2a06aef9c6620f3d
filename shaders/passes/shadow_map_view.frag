#version 460
// The `shadow` debug view: the sun's shadow map, its cascades side by side (left to right, near
// to far), depth 0 (at the sun) white to 1 (far side of the scene) black.
layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 color;
layout(set = 0, binding = 0) uniform sampler2DArray sun_shadow;

void main() {
    float layers = float(textureSize(sun_shadow, 0).z);
    float layer = min(floor(uv.x * layers), layers - 1.0);
    vec2 t = vec2(fract(uv.x * layers), uv.y);
    float d = textureLod(sun_shadow, vec3(t, layer), 0.0).r;
    color = vec4(vec3(1.0 - d), 1.0);
}

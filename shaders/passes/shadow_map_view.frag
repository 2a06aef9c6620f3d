#version 460
// The `shadow` debug view: the sun's shadow maps, one per cascade side by side (left to right, near
// to far), depth 0 (at the sun) white to 1 (far side of the scene) black.
#ifndef RG_SUN_CASCADES
#define RG_SUN_CASCADES 1
#endif
layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 color;
layout(set = 0, binding = 0) uniform sampler2D sun_shadow0;
#if RG_SUN_CASCADES > 1
layout(set = 0, binding = 1) uniform sampler2D sun_shadow1;
#endif
#if RG_SUN_CASCADES > 2
layout(set = 0, binding = 2) uniform sampler2D sun_shadow2;
#endif
#if RG_SUN_CASCADES > 3
layout(set = 0, binding = 3) uniform sampler2D sun_shadow3;
#endif

void main() {
    const float layers = float(RG_SUN_CASCADES);
    int layer = int(min(floor(uv.x * layers), layers - 1.0));
    vec2 t = vec2(fract(uv.x * layers), uv.y);
    float d = textureLod(sun_shadow0, t, 0.0).r;
#if RG_SUN_CASCADES > 1
    if (layer == 1) d = textureLod(sun_shadow1, t, 0.0).r;
#endif
#if RG_SUN_CASCADES > 2
    if (layer == 2) d = textureLod(sun_shadow2, t, 0.0).r;
#endif
#if RG_SUN_CASCADES > 3
    if (layer == 3) d = textureLod(sun_shadow3, t, 0.0).r;
#endif
    color = vec4(vec3(1.0 - d), 1.0);
}

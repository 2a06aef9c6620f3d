#version 460
// The `shadow:LIGHT` debug view: a local light's shadow maps this frame (lib/shadows.glsl's views
// of light `light`): a spot's one map over the image, a cube's six faces in a 3 × 2 grid (+x −x +y
// on top, −y +z −z below); distance from the light white (near) to black (the light's range).
// Magenta: the light has no views this frame (its range does not reach the view).
#define RG_SHADOW_VIEWS 1
#include "lib/scene.glsl"
#include "lib/shadows.glsl"
layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 color;
layout(set = 0, binding = 0) uniform sampler2DArray local_shadow;
layout(set = 0, binding = 1) uniform Params { float light; } params;

void main() {
    ivec4 lv = rgShadowViews.lightViews[int(params.light + 0.5)];
    if (lv.y <= 0) { color = vec4(1.0, 0.0, 1.0, 1.0); return; }
    vec2 t = uv;
    int face = 0;
    if (lv.y == 6) {
        vec2 cell = floor(uv * vec2(3.0, 2.0));
        face = int(cell.x + 3.0 * cell.y);
        t = fract(uv * vec2(3.0, 2.0));
    }
    int vi = lv.x + face;
    RgShadowView v = rgShadowViews.view[vi];
    float d = textureLod(local_shadow, vec3(t, float(vi)), 0.0).r;
    color = vec4(vec3(1.0 - clamp(rgShadowViewDistance(v, d) / v.params.x, 0.0, 1.0)), 1.0);
}

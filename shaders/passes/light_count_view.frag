#version 460
// The `lights` debug view: how many lights reach each 4x4 tile (scripts/lighting.lua's tile) (light_culling.comp's lists: the
// global ones plus the tile's): black 0, then blue -> green -> yellow -> red at 32 and more;
// magenta where more ranged lights reach the tile than its list holds, or a froxel over it lost some. Pixels where nothing was drawn are dimmed.
#include "lib/lighting.glsl"

layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 color;
layout(set = 0, binding = 0) uniform sampler2D depth;

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    RgLightList list = rgLightList(p);
    uint total = list.global + rgTileLightTotal(p);  // the lights that reach every pixel + the tile's
    vec3 c;
    if (total > list.count || rgTileIncomplete(p)) {
        c = vec3(1.0, 0.0, 1.0);
    } else {
        float t = clamp(float(total) / 32.0, 0.0, 1.0);
        c = total == 0u ? vec3(0.0)
                        : clamp(vec3(smoothstep(0.35, 0.7, t), smoothstep(0.0, 0.4, t) - smoothstep(0.75, 1.0, t),
                                     1.0 - smoothstep(0.2, 0.5, t)), 0.0, 1.0);
    }
    if (texelFetch(depth, p, 0).r >= 1.0) c *= 0.35;
    color = vec4(c, 1.0);
}

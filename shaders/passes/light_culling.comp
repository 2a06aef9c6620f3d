#version 460
// Light culling per screen tile (tiled deferred shading; DESIGN §3): one invocation per tile of
// RG_TILE_SIZE² pixels (the pass's `tile` parameter) finds the depth range of the tile's surfaces,
// bounds them by the view-space box of the tile's frustum between those depths, and keeps the
// lights whose sphere of influence — the range of lst:4's window, by the distance to the light's
// centre, which also ends area lights (lighting.glsl rgRangeWindow) — meets that box. Lights
// without a range, and the sun, reach every pixel: they go once into a global list (written by
// the first invocation) rather than into every tile's. Lists are in ascending light order.
//
// One invocation per tile rather than a work group per tile: lavapipe runs a work group's
// invocations as SIMD lanes and switches between them at every barrier, so shared-memory
// reductions cost more than each lane walking its own 256 depths (DESIGN §8).
//
// light_tiles (lib/light_tiles.glsl): header (tiles x, tiles y, stride, tile size), the global
// list (count + RG_MAX_LIGHTS indices), then per tile `stride` words: how many ranged lights reach
// the tile, then their indices. The stride is what the buffer holds per tile (declared with
// tile = RG_TILE_SIZE), at most every light + 1; when more ranged lights reach a tile than its
// list holds, the list keeps the lowest indices (readers clamp; the `lights` view shows it).
#define RG_LIGHT_TILES_WRITER
#include "lib/scene.glsl"
#include "lib/light_tiles.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 0) uniform sampler2D depth;
layout(set = 0, binding = 1, std430) writeonly buffer light_tiles {
    uvec4 header;
    uint global[RG_MAX_LIGHTS + 1];
    uint data[];
} tiles;

bool rgReachesEverything(RgLight light) {
    return int(light.positionType.w + 0.5) == RG_LIGHT_SUN || light.directionRange.w <= 0.0;
}

void main() {
    const ivec2 size = textureSize(depth, 0);
    const uvec2 tileCount = (uvec2(size) + uvec2(RG_TILE_SIZE - 1)) / uvec2(RG_TILE_SIZE);
    const uvec2 t = gl_GlobalInvocationID.xy;
    if (any(greaterThanEqual(t, tileCount))) return;
    const uint tile = t.y * tileCount.x + t.x;
    // A buffer sized for fewer tiles than the depth has (declared for another size) gets a
    // stride below 2: then no tile lists at all, rather than lists that overlap.
    const uint stride = min(uint(tiles.data.length()) / (tileCount.x * tileCount.y), uint(RG_MAX_LIGHTS) + 1u);
    if (tile == 0u) {
        tiles.header = uvec4(tileCount, stride, RG_TILE_SIZE);
        uint n = 0u;
        for (uint i = 0u; i < lights.count.x; ++i)
            if (rgReachesEverything(lights.light[i])) tiles.global[1u + n++] = i;
        tiles.global[0] = n;
    }
    if (stride < 2u) return;

    // The depth range over the pixels something was drawn on (depth < 1).
    const ivec2 first = ivec2(t * uvec2(RG_TILE_SIZE));
    const ivec2 last = min(first + ivec2(RG_TILE_SIZE), size);
    float minDepth = 1.0, maxDepth = 0.0;
    for (int y = first.y; y < last.y; ++y)
        for (int x = first.x; x < last.x; ++x) {
            float d = texelFetch(depth, ivec2(x, y), 0).r;
            if (d < 1.0) {
                minDepth = min(minDepth, d);
                maxDepth = max(maxDepth, d);
            }
        }
    uint count = 0u;
    if (minDepth <= maxDepth) {
        // The view-space box of the tile's frustum between the two depths: its 8 corners.
        vec2 lo = vec2(first) / vec2(size), hi = vec2(last) / vec2(size);
        vec3 boxMin = vec3(1e30), boxMax = vec3(-1e30);
        for (int c = 0; c < 8; ++c) {
            vec2 uv = vec2((c & 1) != 0 ? hi.x : lo.x, (c & 2) != 0 ? hi.y : lo.y);
            vec4 world = camera.invViewProj * vec4(uv * 2.0 - 1.0, (c & 4) != 0 ? maxDepth : minDepth, 1.0);
            vec3 v = (camera.view * vec4(world.xyz / world.w, 1.0)).xyz;
            boxMin = min(boxMin, v);
            boxMax = max(boxMax, v);
        }
        const uint base = tile * stride + 1u;
        for (uint i = 0u; i < lights.count.x; ++i) {
            RgLight light = lights.light[i];
            if (rgReachesEverything(light)) continue;  // in the global list
            vec3 centre = (camera.view * vec4(light.positionType.xyz, 1.0)).xyz;
            vec3 outside = max(max(boxMin - centre, centre - boxMax), vec3(0.0));
            if (dot(outside, outside) * light.directionRange.w < 1.0) {  // distance to the box < range
                if (count < stride - 1u) tiles.data[base + count] = i;
                ++count;
            }
        }
    }
    tiles.data[tile * stride] = count;
}

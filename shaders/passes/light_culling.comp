#version 460
// Light culling per screen tile (tiled deferred shading; DESIGN §3), in two levels
// (scripts/lighting.lua): `light_culling_coarse` (built with RG_CULL_COARSE) lists, per
// RG_COARSE_TILE_SIZE² tile, the ranged lights that reach its surfaces out of every light of the
// scene; `light_culling` then lists, per RG_TILE_SIZE² tile (the tiles the lighting passes read),
// those of its coarse tile's list that reach its own surfaces. A tile's test: the depth range of
// its surfaces bounds the view-space box of the tile's frustum between those depths, and a light
// is kept when its sphere of influence — the range of lst:4's window, by the distance to the
// light's centre, which also ends area lights (lighting.glsl rgRangeWindow) — meets that box.
// Lights without a range, and the sun, reach every pixel: they go once into a global list (written
// by the fine pass's first invocation) rather than into every tile's. Lists are in ascending
// light order.
//
// Why two levels: small tiles keep the lighting's loop to the lights near its pixels (a tile
// reaches every light around its own footprint), but one pass testing every light for every
// small tile costs tiles × lights (8.9 ms for 1024 lights at 640×360 with 8×8 tiles); the coarse
// level makes the fine test cost tiles × the few lights near them.
//
// One invocation per tile rather than a work group per tile: lavapipe runs a work group's
// invocations as SIMD lanes and switches between them at every barrier, so shared-memory
// reductions cost more than each lane walking its own depths (DESIGN §8).
//
// Layouts (lib/light_tiles.glsl): light_tiles: header (tiles x, tiles y, stride, tile size), the
// global list (count + RG_MAX_LIGHTS indices), then per tile `stride` words: how many ranged lights
// reach the tile, then their indices, two 16-bit ones per word. light_tiles_coarse: the header,
// then per coarse tile the count and one index per word. A stride is what the buffer holds per tile (declared with the pass's tile size), at most
// every light + 1; when more ranged lights reach a tile than its list holds, the list keeps the
// lowest indices (readers clamp; the `lights` view shows it).
#define RG_LIGHT_TILES_WRITER
#include "lib/scene.glsl"
#include "lib/light_tiles.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 0) uniform sampler2D depth;
#ifdef RG_CULL_COARSE
#define TILE RG_COARSE_TILE_SIZE
layout(set = 0, binding = 1, std430) writeonly buffer light_tiles_coarse {
    uvec4 header;
    uint data[];
} tiles;
#else
#define TILE RG_TILE_SIZE
layout(set = 0, binding = 1, std430) writeonly buffer light_tiles {
    uvec4 header;
    uint global[RG_MAX_LIGHTS + 1];
    uint data[];
} tiles;
layout(set = 0, binding = 2, std430) readonly buffer light_tiles_coarse {
    uvec4 header;  // tiles x, tiles y, stride, tile size
    uint data[];
} coarse;
#endif

bool rgReachesEverything(RgLight light) {
    return int(light.positionType.w + 0.5) == RG_LIGHT_SUN || light.directionRange.w <= 0.0;
}

void main() {
    const ivec2 size = textureSize(depth, 0);
    const uvec2 tileCount = (uvec2(size) + uvec2(TILE - 1)) / uvec2(TILE);
    const uvec2 t = gl_GlobalInvocationID.xy;
    if (any(greaterThanEqual(t, tileCount))) return;
    const uint tile = t.y * tileCount.x + t.x;
    // A buffer sized for fewer tiles than the depth has (declared for another size) gets a
    // stride below 2: then no tile lists at all, rather than lists that overlap.
    const uint stride = min(uint(tiles.data.length()) / (tileCount.x * tileCount.y), uint(RG_MAX_LIGHTS) + 1u);
    if (tile == 0u) {
        tiles.header = uvec4(tileCount, stride, TILE);
#ifndef RG_CULL_COARSE
        uint n = 0u;
        for (uint i = 0u; i < lights.count.x; ++i)
            if (rgReachesEverything(lights.light[i])) tiles.global[1u + n++] = i;
        tiles.global[0] = n;
#endif
    }
    if (stride < 2u) return;

    // The depth range over the pixels something was drawn on (depth < 1).
    const ivec2 first = ivec2(t * uvec2(TILE));
    const ivec2 last = min(first + ivec2(TILE), size);
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
#ifdef RG_CULL_COARSE
        // Every light of the scene.
        const uint candidates = lights.count.x;
#else
        // The lights of the coarse tile holding this one (every light when the coarse buffer has
        // no room for lists).
        const uint coarseStride = coarse.header.z;
        const uvec2 ct = t * uvec2(TILE) / max(coarse.header.w, 1u);
        const uint coarseBase = (ct.y * coarse.header.x + ct.x) * coarseStride;
        // A coarse list that overflowed lost lights: then this tile tests them all.
        const bool coarseLists = coarseStride >= 2u && coarse.header.w > 0u && coarse.data[coarseBase] < coarseStride;
        const uint candidates = coarseLists ? coarse.data[coarseBase] : lights.count.x;
#endif
        uint pending = 0u;  // fine lists: the lower half of the word being filled
        for (uint k = 0u; k < candidates; ++k) {
#ifdef RG_CULL_COARSE
            const uint i = k;
#else
            const uint i = coarseLists ? coarse.data[coarseBase + 1u + k] : k;
#endif
            RgLight light = lights.light[i];
            if (rgReachesEverything(light)) continue;  // in the global list
            vec3 centre = (camera.view * vec4(light.positionType.xyz, 1.0)).xyz;
            vec3 outside = max(max(boxMin - centre, centre - boxMax), vec3(0.0));
            if (dot(outside, outside) * light.directionRange.w < 1.0) {  // distance to the box < range
#ifdef RG_CULL_COARSE
                if (count < stride - 1u) tiles.data[base + count] = i;
#else
                // Two 16-bit indices per word (lib/light_tiles.glsl), the word written once full.
                if (count < rgTileCapacity(stride)) {
                    if ((count & 1u) == 0u) pending = i;
                    else tiles.data[base + (count >> 1u)] = pending | (i << 16u);
                }
#endif
                ++count;
            }
        }
#ifndef RG_CULL_COARSE
        if ((count & 1u) == 1u && count <= rgTileCapacity(stride)) tiles.data[base + (count >> 1u)] = pending;
#endif
    }
    tiles.data[tile * stride] = count;
}

// The light lists of shaders/passes/light_culling.comp, and the light loop's view of them. A
// lighting shader loops over
//     RgLightList list = rgLightList(ivec2(gl_FragCoord.xy));
//     for (uint k = 0u; k < list.count; ++k) { uint i = rgListLight(list, k); ... }
// With RG_LIGHT_TILES defined (the pass's `defines`, and `{ "light_tiles", as = "storage" }` in its
// reads) that is the lights that reach every pixel (the sun, lights without a range) followed by
// the pixel's tile's ranged lights; without, every light of the scene — so one shader works with
// and without culling.
#ifndef RG_LIGHT_TILES_GLSL
#define RG_LIGHT_TILES_GLSL

#include "lib/scene.glsl"

// Pixels per tile side; the culling pass runs one invocation per tile. The light_tiles buffer is
// declared with the same tile size (rg.buffer { tile = 8, tile_bytes = ... }, scripts/lighting.lua)
// and room for the global list: size = 16 + 4 · (RG_MAX_LIGHTS + 1). The coarse level
// (light_tiles_coarse, written first) has tiles of RG_COARSE_TILE_SIZE pixels.
#ifndef RG_TILE_SIZE
#define RG_TILE_SIZE 8
#endif
#ifndef RG_COARSE_TILE_SIZE
#define RG_COARSE_TILE_SIZE 32
#endif

#ifndef RG_LIGHT_TILES_BINDING
#define RG_LIGHT_TILES_BINDING 12
#endif

struct RgLightList {
    uint base;    // index of the tile's first word after its count in light_tiles.data
    uint count;   // global lights + the tile's
    uint global;  // how many of them come from the global list
};

// A tile's list holds two 16-bit light indices per word (RG_MAX_LIGHTS ≤ 65536), the lower half
// first: `stride` words hold the count and 2 (stride − 1) lights.
uint rgTileCapacity(uint stride) { return 2u * (stride - 1u); }

#if defined(RG_LIGHT_TILES) && !defined(RG_LIGHT_TILES_WRITER)
layout(set = 0, binding = RG_LIGHT_TILES_BINDING, std430) readonly buffer light_tiles {
    uvec4 header;                    // tiles x, tiles y, stride (words per tile), tile size
    uint global[RG_MAX_LIGHTS + 1];  // count, then the lights that reach every pixel
    uint data[];                     // per tile: count, then the ranged lights that reach it (16 bits each)
} lightTiles;

uint rgLightTileIndex(ivec2 pixel) {
    uvec2 t = uvec2(pixel) / lightTiles.header.w;
    return t.y * lightTiles.header.x + t.x;
}
// How many ranged lights reach the tile (may exceed what its list holds: see rgLightList).
uint rgTileLightTotal(ivec2 pixel) {
    return lightTiles.header.z < 2u ? 0u : lightTiles.data[rgLightTileIndex(pixel) * lightTiles.header.z];
}
RgLightList rgLightList(ivec2 pixel) {
    uint stride = lightTiles.header.z;
    uint global = lightTiles.global[0];
    if (stride < 2u) return RgLightList(0u, global, global);  // no room for tile lists
    uint base = rgLightTileIndex(pixel) * stride;
    return RgLightList(base + 1u, global + min(lightTiles.data[base], rgTileCapacity(stride)), global);
}
uint rgListLight(RgLightList list, uint k) {
    if (k < list.global) return lightTiles.global[1u + k];
    uint j = k - list.global;
    return (lightTiles.data[list.base + (j >> 1u)] >> ((j & 1u) * 16u)) & 0xFFFFu;
}
#else
RgLightList rgLightList(ivec2 pixel) { return RgLightList(0u, lights.count.x, 0u); }
uint rgListLight(RgLightList list, uint k) { return k; }
#endif

#endif

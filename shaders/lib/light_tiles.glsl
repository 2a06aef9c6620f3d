// The per-tile light lists of shaders/passes/light_culling.comp, and the light loop's view of
// them. A lighting shader loops over
//     RgLightList list = rgLightList(ivec2(gl_FragCoord.xy));
//     for (uint k = 0u; k < list.count; ++k) { uint i = rgListLight(list, k); ... }
// With RG_LIGHT_TILES defined (the pass's `defines`, and `{ "light_tiles", as = "storage" }` in its
// reads) that is the pixel's tile's list; without, every light of the scene — so one shader works
// with and without culling.
#ifndef RG_LIGHT_TILES_GLSL
#define RG_LIGHT_TILES_GLSL

#include "lib/scene.glsl"

// Pixels per tile side; the culling pass's work group is RG_TILE_SIZE². The light_tiles buffer is
// declared with the same tile size (rg.buffer { tile = 16, tile_bytes = ... }).
#define RG_TILE_SIZE 16

#ifndef RG_LIGHT_TILES_BINDING
#define RG_LIGHT_TILES_BINDING 12
#endif

struct RgLightList {
    uint base;   // index of the tile's first light in light_tiles.data (0 without tiles)
    uint count;
};

#if defined(RG_LIGHT_TILES) && !defined(RG_LIGHT_TILES_WRITER)
layout(set = 0, binding = RG_LIGHT_TILES_BINDING, std430) readonly buffer light_tiles {
    uvec4 header;  // tiles x, tiles y, stride (words per tile), tile size
    uint data[];
} lightTiles;

uint rgLightTileIndex(ivec2 pixel) {
    uvec2 t = uvec2(pixel) / lightTiles.header.w;
    return t.y * lightTiles.header.x + t.x;
}
// How many lights reach the tile (may exceed what its list holds: see rgLightList).
uint rgTileLightTotal(ivec2 pixel) { return lightTiles.data[rgLightTileIndex(pixel) * lightTiles.header.z]; }
RgLightList rgLightList(ivec2 pixel) {
    uint base = rgLightTileIndex(pixel) * lightTiles.header.z;
    return RgLightList(base + 1u, min(lightTiles.data[base], lightTiles.header.z - 1u));
}
uint rgListLight(RgLightList list, uint k) { return lightTiles.data[list.base + k]; }
#else
RgLightList rgLightList(ivec2 pixel) { return RgLightList(0u, lights.count.x); }
uint rgListLight(RgLightList list, uint k) { return k; }
#endif

#endif

// The light lists of shaders/passes/light_culling.comp, and the light loop's view of them. A
// lighting shader loops over
//     RgLightList list = rgLightList(ivec2(gl_FragCoord.xy));
//     for (uint k = 0u; k < list.count; ++k) { uint i = rgListLight(list, k); ... }
// With RG_LIGHT_TILES defined (the pass's `defines`, and `{ "light_tiles", as = "storage" }` in its
// reads) that is the lights that reach every pixel (the sun, lights without a range) followed by
// the pixel's tile's ranged lights (RG_GLOBAL_LIGHTS alone declares the first list); with RG_LIGHT_FROXELS (a forward pass: `lighting.clustered`),
// those of the fragment's froxel; without either, every light of the scene — so one shader works
// with and without culling.
#ifndef RG_LIGHT_TILES_GLSL
#define RG_LIGHT_TILES_GLSL

#include "lib/scene.glsl"

// Pixels per tile side; the culling pass runs one invocation per tile. The light_tiles buffer is
// declared with the same tile size (rg.buffer { tile = 4, tile_bytes = ... }, scripts/lighting.lua).
// The froxel grid (light_froxels, written first) has columns of RG_COARSE_TILE_SIZE pixels, each
// cut into RG_FROXEL_SLICES slices of view distance.
#ifndef RG_TILE_SIZE
#define RG_TILE_SIZE 8
#endif
#ifndef RG_COARSE_TILE_SIZE
#define RG_COARSE_TILE_SIZE 32
#endif
#ifndef RG_FROXEL_SLICES
#define RG_FROXEL_SLICES 16
#endif

#ifndef RG_LIGHT_TILES_BINDING
#define RG_LIGHT_TILES_BINDING 12
#endif

// The lights that reach every pixel — the sun, lights without a range — in light order: a list of
// the scene's (passes/gpu_scene.cpp), made once when it loads, as the lights are.
#ifndef RG_GLOBAL_LIGHTS_BINDING
#define RG_GLOBAL_LIGHTS_BINDING 37
#endif
#if defined(RG_LIGHT_TILES) || defined(RG_LIGHT_FROXELS) || defined(RG_LIGHT_TILES_WRITER) || defined(RG_GLOBAL_LIGHTS)
layout(set = RG_CAMERA_SET, binding = RG_GLOBAL_LIGHTS_BINDING, std430) readonly buffer GlobalLights {
    uvec4 count;   // x: how many
    uint light[];  // their indices, ascending
} globalLights;
#endif

// Whether a light reaches every pixel (the global list's rule; passes/gpu_scene.cpp's twin).
bool rgReachesEverything(RgLight light) {
    return int(light.positionType.w + 0.5) == RG_LIGHT_SUN || light.directionRange.w <= 0.0;
}

// ---- The froxel grid --------------------------------------------------------------------------
// Slices of view distance d over the depths the scene's bounds span (within the near and far
// planes): geometric for a perspective camera (d_k = near · (far/near)^(k/S), each slice as
// deep as it is far away, so a froxel is about as deep as it is wide), even for an orthographic
// one. A distance outside falls in the first or last slice, for writers and readers alike.
struct RgFroxelRange {
    float near, far;
};
RgFroxelRange rgFroxelRange() {
    float a = rgViewDistance(0.0), b = rgViewDistance(1.0);
    // The scene's bounds along the view axis: the nearest and farthest of its box's corners (a
    // linear function is extreme at a corner), within the near and far planes.
    float nearest = 1e30, farthest = -1e30;
    for (int c = 0; c < 8; ++c) {
        vec3 corner = vec3((c & 1) != 0 ? camera.sceneMax.x : camera.sceneMin.x, (c & 2) != 0 ? camera.sceneMax.y : camera.sceneMin.y,
                           (c & 4) != 0 ? camera.sceneMax.z : camera.sceneMin.z);
        float d = rgViewDepth(corner);
        nearest = min(nearest, d);
        farthest = max(farthest, d);
    }
    float near = max(min(a, b), nearest);
    if (!rgCameraOrthographic()) near = max(near, 1e-4);
    float far = min(farthest, max(a, b));
    return RgFroxelRange(near, max(far, near * 1.01 + 1e-3));
}
uint rgFroxelSlice(RgFroxelRange r, float d) {
    float t = rgCameraOrthographic() ? (d - r.near) / (r.far - r.near) : log(max(d, r.near) / r.near) / log(r.far / r.near);
    return uint(clamp(int(floor(t * float(RG_FROXEL_SLICES))), 0, RG_FROXEL_SLICES - 1));
}
// Where slice k begins (k = RG_FROXEL_SLICES: where the last ends).
float rgFroxelSliceStart(RgFroxelRange r, uint k) {
    float t = float(k) / float(RG_FROXEL_SLICES);
    return rgCameraOrthographic() ? mix(r.near, r.far, t) : r.near * pow(r.far / r.near, t);
}
// The view-space point at normalised screen position ndc (−1..1) and view distance d.
vec3 rgViewPointAt(vec2 ndc, float d) {
    if (rgCameraOrthographic())
        return vec3((ndc.x - camera.proj[3][0]) / camera.proj[0][0], (ndc.y - camera.proj[3][1]) / camera.proj[1][1], -d);
    return vec3(ndc.x * d / camera.proj[0][0], ndc.y * d / camera.proj[1][1], -d);
}
// The four side planes through the eye of a perspective frustum whose edges pass through
// `corner` (view space, in order around it), their normals pointing inside: what the light
// culling tests a light's sphere against besides a box (shaders/passes/light_froxels.comp per
// column, light_culling.comp per tile; an orthographic frustum's sides are its boxes' own).
void rgFrustumSides(vec3 corner[4], out vec3 sides[4]) {
    const vec3 middle = 0.25 * (corner[0] + corner[1] + corner[2] + corner[3]);
    for (int c = 0; c < 4; ++c) {
        vec3 n = cross(corner[c], corner[(c + 1) & 3]);
        n *= inversesqrt(max(dot(n, n), 1e-30));
        sides[c] = dot(n, middle) < 0.0 ? -n : n;
    }
}
// Whether a sphere (view-space centre, radius) is not wholly outside any of those planes.
bool rgSphereMeetsSides(vec3 sides[4], vec3 centre, float radius) {
    bool meets = true;
    for (int c = 0; c < 4; ++c) meets = meets && dot(sides[c], centre) > -radius;
    return meets;
}

struct RgLightList {
    uint base;    // index of the tile's first word after its count in light_tiles.data
    uint count;   // global lights + the tile's
    uint global;  // how many of them come from the global list
};

// A tile's list holds two 16-bit light indices per word (RG_MAX_LIGHTS ≤ 65536), the lower half
// first: `stride` words hold the count and 2 (stride − 1) lights.
uint rgTileCapacity(uint stride) { return 2u * (stride - 1u); }
// Entry k of a list of 16-bit light indices (tiles' and froxels' alike) out of its word k / 2.
uint rgListEntry(uint word, uint k) { return (word >> ((k & 1u) * 16u)) & 0xFFFFu; }
// Set in a tile's count when a froxel it read had lost lights (more reached it than its list held).
#define RG_TILE_INCOMPLETE 0x80000000u

#if defined(RG_LIGHT_TILES) && !defined(RG_LIGHT_TILES_WRITER)
layout(set = 0, binding = RG_LIGHT_TILES_BINDING, std430) readonly buffer light_tiles {
    uvec4 header;  // tiles x, tiles y, stride (words per tile), tile size
    uint data[];   // per tile: count, then the ranged lights that reach it (16 bits each)
} lightTiles;

uint rgLightTileIndex(ivec2 pixel) {
    uvec2 t = uvec2(pixel) / lightTiles.header.w;
    return t.y * lightTiles.header.x + t.x;
}
// How many ranged lights reach the tile (may exceed what its list holds: see rgLightList).
uint rgTileLightTotal(ivec2 pixel) {
    return lightTiles.header.z < 2u ? 0u : lightTiles.data[rgLightTileIndex(pixel) * lightTiles.header.z] & ~RG_TILE_INCOMPLETE;
}
// Whether the tile's list may lack lights that reach it: a froxel over it overflowed.
bool rgTileIncomplete(ivec2 pixel) {
    return lightTiles.header.z >= 2u && (lightTiles.data[rgLightTileIndex(pixel) * lightTiles.header.z] & RG_TILE_INCOMPLETE) != 0u;
}
RgLightList rgLightList(ivec2 pixel) {
    uint stride = lightTiles.header.z;
    uint global = globalLights.count.x;
    if (stride < 2u) return RgLightList(0u, global, global);  // no room for tile lists
    uint base = rgLightTileIndex(pixel) * stride;
    return RgLightList(base + 1u, global + min(lightTiles.data[base] & ~RG_TILE_INCOMPLETE, rgTileCapacity(stride)), global);
}
uint rgListLight(RgLightList list, uint k) {
    if (k < list.global) return globalLights.light[k];
    uint j = k - list.global;
    return rgListEntry(lightTiles.data[list.base + (j >> 1u)], j);
}
#elif defined(RG_LIGHT_FROXELS) && !defined(RG_LIGHT_TILES_WRITER)
// A pass without a depth buffer of its own surfaces (forward: blended surfaces over the opaque
// ones) reads the froxel grid instead, at its fragment's own depth: the lights that reach every
// pixel, then those of the fragment's froxel (ascending, 16 bits each). A fragment-shader reader.
#ifndef RG_LIGHT_FROXELS_BINDING
#define RG_LIGHT_FROXELS_BINDING 38
#endif
layout(set = 0, binding = RG_LIGHT_FROXELS_BINDING, std430) readonly buffer light_froxel_counts {
    uvec4 header;  // columns x, columns y, slices, stride (words per froxel)
    uint count[];
} froxelCounts;
layout(set = 0, binding = RG_LIGHT_FROXELS_BINDING + 1, std430) readonly buffer light_froxels { uint data[]; } froxelLists;

RgLightList rgLightList(ivec2 pixel) {
    uint global = globalLights.count.x;
    uvec4 h = froxelCounts.header;
    if (h.w == 0u || h.z != uint(RG_FROXEL_SLICES)) return RgLightList(0u, global, global);  // no lists
    uvec2 column = min(uvec2(pixel) / uint(RG_COARSE_TILE_SIZE), h.xy - 1u);
    uint slice = rgFroxelSlice(rgFroxelRange(), rgViewDistance(gl_FragCoord.z));
    uint f = (column.y * h.x + column.x) * h.z + slice;
    return RgLightList(f * h.w, global + min(froxelCounts.count[f], 2u * h.w), global);
}
uint rgListLight(RgLightList list, uint k) {
    if (k < list.global) return globalLights.light[k];
    uint j = k - list.global;
    return rgListEntry(froxelLists.data[list.base + (j >> 1u)], j);
}
#elif !defined(RG_LIGHT_TILES_WRITER)
RgLightList rgLightList(ivec2 pixel) { return RgLightList(0u, lights.count.x, 0u); }
uint rgListLight(RgLightList list, uint k) { return k; }
#endif

#endif

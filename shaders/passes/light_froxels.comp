#version 460
// The froxel grid of light culling (clustered shading; scripts/lighting.lua): columns of
// RG_COARSE_TILE_SIZE² pixels, each cut into RG_FROXEL_SLICES slices of view distance
// (lib/light_tiles.glsl's rgFroxelSlice). Three passes, built from this file:
//
//   `light_froxels` (the default): one invocation per light, striding over the scene's lights (the
//   pass dispatches a fixed number of work groups); with fewer lights than invocations, up to 64
//   invocations a light, each taking a share of its columns. A ranged light's sphere of
//   influence — the range of lst:4's window, which also ends area lights (lighting.glsl
//   rgRangeWindow) — bounds a rectangle of columns (its view-space box projected) and a run of slices (its depth ± range);
//   the light goes into the list of every froxel there whose view-space box it meets, in the
//   columns whose four side planes it does not lie wholly outside, and its sphere in view space
//   into light_spheres (what the fine culling tests). Lists grow by an atomic count, so their
//   order is the order the lights arrived in. A light whose share would test more than
//   RG_FROXEL_LARGE_WORK froxels is listed in light_froxels_large instead.
//   `light_froxels_large` (RG_FROXEL_LARGE): those lights, every invocation of its dispatch taking
//   a share of their columns (a light across a 4K frame: 8 160 columns × 16 slices, more than one
//   invocation may walk on lavapipe).
//   `light_froxels_sort` (RG_FROXEL_SORT): one invocation per froxel (striding over them, the
//   same slice of neighbouring columns side by side) sorts its list into ascending light order,
//   so that every list — and every sum over one — is the same from run to run.
//
// The cost is lights × the froxels each one covers, not froxels × lights: a scene of many small
// lights costs about what a few large ones do (the fine tiles, shaders/passes/light_culling.comp,
// then read only the froxels their surfaces' depths span). Lights that reach every pixel (the sun,
// lights without a range) are in the scene's global list instead.
//
// Layouts: light_froxel_counts: a header (columns x, columns y, slices, stride), then per froxel
// (((y · columns x) + x) · slices + slice) how many lights reach it (cleared each frame by the `light_froxels_clear` pass); light_froxels:
// per froxel `stride` words, two 16-bit light indices each, the lower half first. A froxel reached
// by more lights than its list holds keeps the first that arrived: its count says so, and the tiles
// under it are marked (the `lights` view shows them magenta). No invocation ever walks every light
// or every froxel: lavapipe ends a shader's loops after 65 535 iterations in all, so such a loop
// would stop short without a word. (The pass of large lights still can, with more than ~340
// lights each across a 4K frame: its 1 024 invocations' shares grow with them, and every share
// stops short at the same column, so the last rows of columns lack them without a mark — while
// every froxel they do reach holds more than its 254 lights and marks its tiles.)
#define RG_LIGHT_TILES_WRITER
#include "lib/scene.glsl"
#include "lib/light_tiles.glsl"

layout(local_size_x = 64) in;
layout(set = 0, binding = 0) uniform sampler2D depth;  // its size is the frame's
layout(set = 0, binding = 1, std430) buffer light_froxel_counts {
    uvec4 header;  // columns x, columns y, slices, stride (words per froxel): for readers
    uint count[];
} counts;
layout(set = 0, binding = 2, std430) buffer light_froxels { uint data[]; } froxels;
#if !defined(RG_FROXEL_SORT) && !defined(RG_FROXEL_LARGE)
// Per light its sphere of influence in view space (xyz the centre, w the range with a margin for
// rounding), for the fine culling (light_culling.comp), which tests every light of a froxel's
// list against each tile under it: one load there instead of a light's position, range and the
// view transform.
layout(set = 0, binding = 3, std430) writeonly buffer light_spheres { vec4 sphere[]; } spheres;
#endif

#ifndef RG_FROXEL_SORT
// The lights the binning leaves to `light_froxels_large` (RG_FROXEL_LARGE): a count, then their
// indices in the order they came (the sort orders the lists after both).
layout(set = 0, binding = 4, std430) buffer light_froxels_large {
    uint count;
    uint pad0, pad1, pad2;
    uint light[];
} large;

// Froxels a share of a light's binning may test (its columns × slices) before the light is left
// to the pass of large lights, whose every invocation takes a share: lavapipe ends a shader's
// loops after 65 535 iterations in all (DESIGN §8), and a light across a 4K frame (8 160 columns
// × 16 slices) binned by one invocation lost its last columns without a word.
#ifndef RG_FROXEL_LARGE_WORK
#define RG_FROXEL_LARGE_WORK 4096
#endif

// Bins share `part` of `parts` of light i (every parts-th column of its rectangle): into the list
// of every froxel there whose view-space box its sphere of influence meets, in the columns whose
// four side planes it does not lie wholly outside. `mayDefer`: a share that would test more than
// RG_FROXEL_LARGE_WORK froxels instead leaves the light to the pass of large lights (share 0
// lists it). The binning also writes the light's view-space sphere (share 0). `range`: the
// frame's rgFroxelRange, taken once per invocation.
void rgBinLight(uint i, uint part, uint parts, uvec2 size, uvec2 columns, uint stride, RgFroxelRange range, bool mayDefer) {
    const bool ortho = rgCameraOrthographic();
    const uint capacity = 2u * stride;
    const RgLight light = rgLight(i);
    if (rgReachesEverything(light)) return;  // in the global list
    const vec3 c = (camera.view * vec4(light.positionType.xyz, 1.0)).xyz;
    const float r = inversesqrt(light.directionRange.w);
    const float reach = r * 1.001 + 1e-4;  // the range, with a margin for rounding
#ifndef RG_FROXEL_LARGE
    if (part == 0u && i < uint(spheres.sphere.length())) spheres.sphere[i] = vec4(c, reach);
#endif
    const float dMin = -c.z - r, dMax = -c.z + r;
    if (dMax < range.near) return;  // wholly in front of the near plane
    const uint s0 = rgFroxelSlice(range, max(dMin, range.near)), s1 = rgFroxelSlice(range, dMax);
    // The columns its view-space box covers on screen: the whole screen when the box crosses a
    // perspective camera's near plane.
    vec2 lo = vec2(-1.0), hi = vec2(1.0);
    if (ortho || dMin > range.near) {
        lo = vec2(1e30);
        hi = vec2(-1e30);
        for (int k = 0; k < 8; ++k) {
            vec3 corner = c + r * vec3((k & 1) != 0 ? 1.0 : -1.0, (k & 2) != 0 ? 1.0 : -1.0, (k & 4) != 0 ? 1.0 : -1.0);
            vec4 clip = camera.proj * vec4(corner, 1.0);
            vec2 ndc = clip.xy / clip.w;
            lo = min(lo, ndc);
            hi = max(hi, ndc);
        }
    }
    if (any(greaterThan(lo, vec2(1.0))) || any(lessThan(hi, vec2(-1.0)))) return;  // off screen
    const ivec2 c0 = clamp(ivec2(floor((lo * 0.5 + 0.5) * vec2(size) / float(RG_COARSE_TILE_SIZE))), ivec2(0), ivec2(columns) - 1);
    const ivec2 c1 = clamp(ivec2(floor((hi * 0.5 + 0.5) * vec2(size) / float(RG_COARSE_TILE_SIZE))), ivec2(0), ivec2(columns) - 1);
    const ivec2 extent = c1 - c0 + 1;
    if (mayDefer && uint(extent.x * extent.y) / parts * (s1 - s0 + 1u) > uint(RG_FROXEL_LARGE_WORK)) {
        if (part == 0u) {
            const uint n = atomicAdd(large.count, 1u);
            if (n < uint(large.light.length())) large.light[n] = i;
        }
        return;
    }
    for (int j = int(part); j < extent.x * extent.y; j += int(parts)) {
        const int x = c0.x + j % extent.x, y = c0.y + j / extent.x;
        // The column's four corner rays, in normalised screen coordinates.
        const vec2 a = vec2(ivec2(x, y) * RG_COARSE_TILE_SIZE) / vec2(size) * 2.0 - 1.0;
        const vec2 b = min(vec2(ivec2(x + 1, y + 1) * RG_COARSE_TILE_SIZE) / vec2(size), vec2(1.0)) * 2.0 - 1.0;
        // A perspective column's four side planes through the eye: a sphere wholly outside one
        // meets none of its froxels. Tighter than the froxels' boxes, which off the screen's
        // centre slant far past the column (an orthographic column's sides are its boxes' own).
        if (!ortho) {
            vec3 sides[4];
            rgFrustumSides(vec3[](rgViewPointAt(a, 1.0), rgViewPointAt(vec2(b.x, a.y), 1.0), rgViewPointAt(b, 1.0),
                                  rgViewPointAt(vec2(a.x, b.y), 1.0)),
                           sides);
            if (!rgSphereMeetsSides(sides, c, reach)) continue;
        }
        float d0 = rgFroxelSliceStart(range, s0);
        for (uint s = s0; s <= s1; ++s) {
            // The froxel's view-space box: its 8 corners. The last slice also holds what lies
            // past the scene's far end: there it reaches as far as the light does.
            const float d1 = rgFroxelSliceStart(range, s + 1u);
            const float near = d0, far = s == uint(RG_FROXEL_SLICES - 1) ? max(d1, dMax) : d1;
            vec3 boxMin = vec3(1e30), boxMax = vec3(-1e30);
            for (int k = 0; k < 8; ++k) {
                vec3 v = rgViewPointAt(vec2((k & 1) != 0 ? b.x : a.x, (k & 2) != 0 ? b.y : a.y), (k & 4) != 0 ? far : near);
                boxMin = min(boxMin, v);
                boxMax = max(boxMax, v);
            }
            d0 = d1;
            const vec3 outside = max(max(boxMin - c, c - boxMax), vec3(0.0));
            if (dot(outside, outside) * light.directionRange.w >= 1.0) continue;  // beyond its range
            const uint f = (uint(y) * columns.x + uint(x)) * uint(RG_FROXEL_SLICES) + s;
            const uint n = atomicAdd(counts.count[f], 1u);
            if (n < capacity) {
                // Two lights share a word: each clears and sets its own half (disjoint bits, so
                // the two lanes' atomics commute), whatever the word held.
                const uint word = f * stride + (n >> 1u), shift = (n & 1u) * 16u;
                atomicAnd(froxels.data[word], ~(0xFFFFu << shift));
                atomicOr(froxels.data[word], i << shift);
            }
        }
    }
}
#else
uint entry(uint base, uint k) { return rgListEntry(froxels.data[base + (k >> 1u)], k); }
void setEntry(uint base, uint k, uint v) {
    uint word = froxels.data[base + (k >> 1u)];
    uint shift = (k & 1u) * 16u;
    froxels.data[base + (k >> 1u)] = (word & ~(0xFFFFu << shift)) | (v << shift);
}
#endif

void main() {
    const uvec2 size = uvec2(textureSize(depth, 0));
    const uvec2 columns = (size + uvec2(RG_COARSE_TILE_SIZE - 1)) / uvec2(RG_COARSE_TILE_SIZE);
    const uint froxelCount = columns.x * columns.y * uint(RG_FROXEL_SLICES);
    // Buffers declared for a smaller frame than the depth's: no lists (stride 0).
    const uint stride = uint(counts.count.length()) >= froxelCount ? uint(froxels.data.length()) / froxelCount : 0u;
    const uint capacity = 2u * stride;
    const uint invocations = gl_NumWorkGroups.x * gl_WorkGroupSize.x;
#ifndef RG_FROXEL_SORT
    if (gl_GlobalInvocationID.x == 0u) counts.header = uvec4(columns, uint(RG_FROXEL_SLICES), stride);
#endif
    if (stride == 0u) return;  // a buffer declared for a smaller frame: no lists
#ifdef RG_FROXEL_SORT
    // Insertion sort: the lists are short (tens of lights) and mostly in order already (each
    // invocation of the binning pass takes lights in ascending order). One froxel per invocation
    // as far as the dispatch goes: lavapipe ends a shader's loops after 65 535 iterations in all
    // (DESIGN §8), and a reversed list of 254 takes 32 000.
    // Neighbouring invocations take the same slice of neighbouring columns, whose lists are about
    // as long: a CPU rasteriser runs them as one SIMD's lanes, each loop as long as its longest
    // lane's (neighbouring slices of one column, mostly empty around one full, left 7 of 8
    // lanes idle).
    const uint columnCount = columns.x * columns.y;
    for (uint g = gl_GlobalInvocationID.x; g < froxelCount; g += invocations) {
        const uint f = (g % columnCount) * uint(RG_FROXEL_SLICES) + g / columnCount;
        const uint n = min(counts.count[f], capacity), base = f * stride;
        for (uint k = 1u; k < n; ++k) {
            const uint v = entry(base, k);
            uint j = k;
            for (; j > 0u && entry(base, j - 1u) > v; --j) setEntry(base, j, entry(base, j - 1u));
            if (j != k) setEntry(base, j, v);
        }
    }
#elif defined(RG_FROXEL_LARGE)
    // The lights the binning deferred: every invocation of the dispatch shares their columns.
    const uint largeCount = min(large.count, uint(large.light.length()));
    const uint parts = max(invocations / max(largeCount, 1u), 1u);
    const RgFroxelRange range = rgFroxelRange();
    for (uint g = gl_GlobalInvocationID.x; g < largeCount * parts; g += invocations)
        rgBinLight(large.light[g / parts], g % parts, parts, size, columns, stride, range, false);
#else
    // Few lights each cover many columns: their columns are shared out among `parts` invocations
    // a light (as many as the dispatch has to spare, up to a work group), each taking every
    // parts-th column of the light's rectangle — or 64 lights would be one work group's, on one
    // core, walking thousands of froxels each.
    const uint lightCount = lights.count.x;
    const uint parts = clamp(invocations / max(lightCount, 1u), 1u, 64u);
    const RgFroxelRange range = rgFroxelRange();
    for (uint g = gl_GlobalInvocationID.x; g < lightCount * parts; g += invocations)
        rgBinLight(g / parts, g % parts, parts, size, columns, stride, range, true);
#endif
}

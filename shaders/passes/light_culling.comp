#version 460
// Light culling per screen tile (tiled and clustered deferred shading; DESIGN §3): per
// RG_TILE_SIZE² tile (the tiles the lighting passes read), the ranged lights that reach its
// surfaces, out of the froxels its surfaces' depths span (shaders/passes/light_froxels.comp, run
// before it: per column of RG_COARSE_TILE_SIZE² pixels and slice of view distance, the lights
// whose range meets the froxel). A tile's test: the depth range of its surfaces bounds the
// view-space box of the tile's frustum between those depths, and a light is kept when its sphere
// of influence — the range of lst:4's window, by the distance to the light's centre, which also
// ends area lights (lighting.glsl rgRangeWindow) — meets that box and the inside of the tile
// frustum's four side planes (the box alone slants far past the frustum). Lists are in ascending light
// order: the froxels' sorted lists merged. Lights without a range, and the sun, reach every pixel:
// they are in the scene's global list (lib/light_tiles.glsl), not in any tile's.
//
// Why two levels: small tiles keep the lighting's loop to the lights near its pixels (a tile
// reaches every light around its own footprint), but testing every light for every small tile
// costs tiles × lights (8.9 ms for 1024 lights at 640×360 with 8×8 tiles); the froxels make the
// fine test cost tiles × the few lights near them, and their own cost lights × the froxels each
// covers.
//
// One invocation per tile rather than a work group per tile: lavapipe runs a work group's
// invocations as SIMD lanes and switches between them at every barrier, so shared-memory
// reductions cost more than each lane walking its own depths (DESIGN §8).
//
// Layout (lib/light_tiles.glsl): light_tiles: header (tiles x, tiles y, stride, tile size), then
// per tile `stride` words: how many ranged lights reach the tile, then their indices, two 16-bit
// ones per word. A stride is what the buffer holds per tile (declared with the pass's tile size);
// when more ranged lights reach a tile than its list holds, the list keeps the lowest indices
// (readers clamp; the `lights` view shows it). A tile under a froxel whose list overflowed has
// RG_TILE_INCOMPLETE set in its count (the view shows it too). A tile never walks every light
// instead: lavapipe ends a shader's loops after 65 535 iterations in all (DESIGN §8).
#define RG_LIGHT_TILES_WRITER
#include "lib/scene.glsl"
#include "lib/light_tiles.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 0) uniform sampler2D depth;
layout(set = 0, binding = 1, std430) writeonly buffer light_tiles {
    uvec4 header;
    uint data[];
} tiles;
layout(set = 0, binding = 2, std430) readonly buffer light_froxel_counts {
    uvec4 header;  // columns x, columns y, slices, stride (light_froxels.comp)
    uint count[];
} froxelCounts;
layout(set = 0, binding = 3, std430) readonly buffer light_froxels { uint data[]; } froxels;
// Per light its sphere of influence in view space, as the binning wrote it this frame (xyz the
// centre, w the range with a margin for rounding).
layout(set = 0, binding = 4, std430) readonly buffer light_spheres { vec4 sphere[]; } spheres;

const uint kNoLight = 0xFFFFFFFFu;  // past a list's end

// Entry k of froxel f's list (16-bit light indices, two a word, `stride` words a froxel).
uint rgFroxelEntry(uint f, uint stride, uint k) { return rgListEntry(froxels.data[f * stride + (k >> 1u)], k); }

// Light i of a froxel's list, for the tile whose frustum has view-space box boxMin..boxMax and
// side planes `sides`: appended to the tile's list (`count` so far; `pending` the lower half of
// the word being filled, two 16-bit indices per word, lib/light_tiles.glsl) when its sphere of
// influence meets the box and, for a perspective camera, the inside of every side plane.
void rgConsider(uint i, vec3 boxMin, vec3 boxMax, vec3 sides[4], bool perspective, uint base, uint stride, inout uint count,
                inout uint pending) {
    // The sphere the binning wrote: one load, where the light's position and range and the view
    // transform were 1 ms of 16 at 16 384 lights. Its range has a margin for the rounding of the
    // two reconstructions of a surface's position (this one and the lighting pass's).
    const vec4 sphere = spheres.sphere[i];
    const vec3 centre = sphere.xyz;
    const float reach = sphere.w;
    const vec3 outside = max(max(boxMin - centre, centre - boxMax), vec3(0.0));
    bool reaches = dot(outside, outside) < reach * reach;  // distance to the box < range
    if (reaches && perspective) reaches = rgSphereMeetsSides(sides, centre, reach);
    if (reaches) {
        if (count < rgTileCapacity(stride)) {
            if ((count & 1u) == 0u) pending = i;
            else tiles.data[base + (count >> 1u)] = pending | (i << 16u);  // the word, once full
        }
        ++count;
    }
}

void main() {
    const ivec2 size = textureSize(depth, 0);
    const uvec2 tileCount = (uvec2(size) + uvec2(RG_TILE_SIZE - 1)) / uvec2(RG_TILE_SIZE);
    const uvec2 t = gl_GlobalInvocationID.xy;
    if (any(greaterThanEqual(t, tileCount))) return;
    const uint tile = t.y * tileCount.x + t.x;
    // A buffer sized for fewer tiles than the depth has (declared for another size) gets a
    // stride below 2: then no tile lists at all, rather than lists that overlap.
    const uint stride = min(uint(tiles.data.length()) / (tileCount.x * tileCount.y), uint(RG_MAX_LIGHTS) / 2u + 1u);
    if (tile == 0u) tiles.header = uvec4(tileCount, stride, RG_TILE_SIZE);
    if (stride < 2u) return;

    // The depth range over the pixels something was drawn on (depth < 1). Constant bounds, the
    // frame's edge clamped (a pixel read twice changes no extreme): the compiler unrolls the 16
    // reads, where loops to the edge cost a masked pass each (~0.3 ms at 1280x720 on lavapipe).
    const ivec2 first = ivec2(t * uvec2(RG_TILE_SIZE));
    const ivec2 last = min(first + ivec2(RG_TILE_SIZE), size);
    float minDepth = 1.0, maxDepth = 0.0;
    for (int y = 0; y < RG_TILE_SIZE; ++y)
        for (int x = 0; x < RG_TILE_SIZE; ++x) {
            float d = texelFetch(depth, min(first + ivec2(x, y), last - 1), 0).r;
            if (d < 1.0) {
                minDepth = min(minDepth, d);
                maxDepth = max(maxDepth, d);
            }
        }
    uint count = 0u;
    bool incomplete = false;
    if (minDepth <= maxDepth) {
        // The view-space box of the tile's frustum between the two depths: its 8 corners.
        vec2 lo = vec2(first) / vec2(size), hi = vec2(last) / vec2(size);
        vec3 boxMin = vec3(1e30), boxMax = vec3(-1e30), nearCorner[4];
        for (int c = 0; c < 8; ++c) {
            vec2 uv = vec2((c & 1) != 0 ? hi.x : lo.x, (c & 2) != 0 ? hi.y : lo.y);
            vec4 world = camera.invViewProj * vec4(uv * 2.0 - 1.0, (c & 4) != 0 ? maxDepth : minDepth, 1.0);
            vec3 v = (camera.view * vec4(world.xyz / world.w, 1.0)).xyz;
            boxMin = min(boxMin, v);
            boxMax = max(boxMax, v);
            if (c < 4) nearCorner[c] = v;
        }
        const uint base = tile * stride + 1u;
        // The box holds far more than the tile sees where the tile's frustum slants (off the
        // screen's centre, by up to its depth range × the ray's slope each way: a tile across a
        // sphere's silhouette, which spans the floor behind it, kept 82 of 16 384 lights in the
        // many-lights scene). So a light whose sphere meets the box is kept only when it also
        // meets the inside of each of the frustum's four side planes through the eye (a
        // perspective's; an orthographic frustum's sides are the box's own).
        const bool perspective = !rgCameraOrthographic();
        vec3 sides[4];
        rgFrustumSides(vec3[](nearCorner[0], nearCorner[1], nearCorner[3], nearCorner[2]), sides);  // around the tile

        // The froxels of the tile's column its depths span, and how much each list holds.
        const uvec2 columns = (uvec2(size) + uvec2(RG_COARSE_TILE_SIZE - 1)) / uvec2(RG_COARSE_TILE_SIZE);
        const uvec2 column = t * uvec2(RG_TILE_SIZE) / uvec2(RG_COARSE_TILE_SIZE);
        const uint froxelStride = froxelCounts.header.w;
        const RgFroxelRange range = rgFroxelRange();
        const float dA = rgViewDistance(minDepth), dB = rgViewDistance(maxDepth);
        const uint s0 = rgFroxelSlice(range, min(dA, dB)), s1 = rgFroxelSlice(range, max(dA, dB));
        const uint froxel0 = (column.y * columns.x + column.x) * uint(RG_FROXEL_SLICES);
        // A froxel whose list overflowed lost lights, and froxels without room for lists (a
        // buffer declared for a smaller frame) hold none of the ranged lights: either way the
        // tile's list is marked incomplete.
        incomplete = froxelStride == 0u && lights.count.x > globalLights.count.x;
        for (uint s = s0; s <= s1; ++s) incomplete = incomplete || froxelCounts.count[froxel0 + s] > 2u * froxelStride;
        // Merge the froxels' ascending lists (a light in several is taken once).
        uint cursor[RG_FROXEL_SLICES], length[RG_FROXEL_SLICES];
        for (uint s = s0; s <= s1; ++s) {
            cursor[s] = 0u;
            length[s] = min(froxelCounts.count[froxel0 + s], 2u * froxelStride);
        }
        uint pending = 0u;  // the lower half of the word being filled
        if (s1 <= s0 + 1u) {
            // Most tiles' surfaces lie in one slice, most others in two: a two-way merge with
            // both lists' heads in registers (a one-slice tile's second list is empty), one load
            // a step (two where both heads hold the light). The k-way merge below reloads every list's head twice a step: run for the
            // two-slice tiles too, it cost ~1.8 ms of ~13.8 at 16 384 lights (many-lights scene,
            // 1280x720 on lavapipe), where a SIMD with one such tile among its lanes ran it.
            const uint lenA = length[s0], lenB = s1 > s0 ? length[s1] : 0u;
            uint kA = 0u, kB = 0u;
            uint headA = lenA > 0u ? rgFroxelEntry(froxel0 + s0, froxelStride, 0u) : kNoLight;
            uint headB = lenB > 0u ? rgFroxelEntry(froxel0 + s1, froxelStride, 0u) : kNoLight;
            for (uint i = min(headA, headB); i != kNoLight; i = min(headA, headB)) {
                rgConsider(i, boxMin, boxMax, sides, perspective, base, stride, count, pending);
                if (headA == i) headA = ++kA < lenA ? rgFroxelEntry(froxel0 + s0, froxelStride, kA) : kNoLight;
                if (headB == i) headB = ++kB < lenB ? rgFroxelEntry(froxel0 + s1, froxelStride, kB) : kNoLight;
            }
        } else {
            // Three slices or more (a depth edge): a k-way merge of their ascending lists.
            for (;;) {
                uint i = kNoLight;
                for (uint s = s0; s <= s1; ++s)
                    if (cursor[s] < length[s]) i = min(i, rgFroxelEntry(froxel0 + s, froxelStride, cursor[s]));
                for (uint s = s0; s <= s1; ++s)
                    if (cursor[s] < length[s] && rgFroxelEntry(froxel0 + s, froxelStride, cursor[s]) == i) ++cursor[s];
                if (i == kNoLight) break;
                rgConsider(i, boxMin, boxMax, sides, perspective, base, stride, count, pending);
            }
        }
        if ((count & 1u) == 1u && count <= rgTileCapacity(stride)) tiles.data[base + (count >> 1u)] = pending;
    }
    tiles.data[tile * stride] = count | (incomplete ? RG_TILE_INCOMPLETE : 0u);
}

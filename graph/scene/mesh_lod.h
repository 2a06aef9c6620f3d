#pragma once
// Levels of detail for meshes that come without them (glTF, the library's meshes, spheres whose
// grid does not halve): meshoptimizer's simplifier at a half, a quarter and an eighth of the
// triangles, each level's error *measured* against the full mesh — the largest distance from a
// vertex of the full mesh to the level's surface and from a point of the level's triangles to the
// full surface — rather than taken from the simplifier's own estimate, which understated a
// sphere's silhouette about threefold. Passes pick by that error projected to a pixel or a texel
// (passes/gpu_scene.h DrawItem::lods), as they do the generated spheres' exact levels.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "scene.h"

namespace rg {

// Primitives with fewer triangles keep none: a level would save less than its draw's setup.
inline constexpr size_t kLodMinTriangles = 256;

using LodStats = Scene::LodStats;

// Gives every primitive of `scene` without levels of detail and with at least kLodMinTriangles
// triangles up to three coarser index lists (a level that drops under 15 % of the triangles of
// the one before ends the chain). Open borders stay where they are, so primitives that meet along
// one do not crack. Levels are kept by the content of the positions and indices in a process-wide
// cache (reloading a scene, hot reload, `serve`: no simplifying again) and, once a folder is set,
// in files there (`<cache>/lods/<hash>.lod`: the next process reads them instead).
// Returns what this call did; `scene.lodStats` sums every call's.
LodStats buildMeshLods(Scene& scene);

// The folder of the levels' files ("" = none, the default); the runtime sets <cache>/lods.
void setMeshLodCacheDir(std::string dir);

// The largest distance from a point of `from` (its vertices, and its triangles' centres and edge
// midpoints) to the surface of `to`, both index lists over `vertices` (metres, their space).
float meshDeviation(const std::vector<Vertex>& vertices, const std::vector<uint32_t>& from,
                    const std::vector<uint32_t>& to);

}  // namespace rg

// Baked global illumination as spherical-Gaussian lightmaps (seed 003, "SG Lightmaps"): the atlas
// the scene's nodes are packed into, the CPU baker (Intel Embree for the ray casts) and the EXR file
// the bake is kept in.
//
// What a texel holds: the radiance arriving at the surface over its upper hemisphere, as the sum of
// N spherical Gaussians with fixed axes and one fixed sharpness (the seed's "Fixed Directions",
// "Fixed Widths") in the texel's tangent frame (tangent, bitangent, normal: the vertex normal and
// tangent interpolated, exactly as lib/material.glsl builds the frame the normal map turns); only
// the N RGB amplitudes are stored, all ≥ 0. The G-buffer pass integrates them against the
// clamped cosine of the shaded normal (lib/lightmap.glsl): the irradiance, × the diffuse albedo / π,
// is the radiosity Frostbite's GB3 holds (seed 000 tbl:2).
//
// Which light goes in (scene API, Light::baked):
//   - the environment (sky) and emissive surfaces: always, directly and bounced;
//   - a light marked `baked = true`: its direct light at the texel and its bounces — the real-time
//     light loop then skips it;
//   - any other light stays dynamic: the real-time loop lights the texel directly, the lightmap holds
//     only what it bounces off other surfaces.
// Surfaces bounce light as Lambertian reflectors of their Disney diffuse albedo (base colour ×
// (1 − metal mask), a two-colour material's diffuse colour); metals are black to the diffuse
// bounce. IES profiles do not shape baked light (a baked IES light is refused).
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/result.h"
#include "scene/scene.h"

namespace rg::bake {

// Where every node lands in the atlas: a square of `side` texels per node with one texel of border
// around it, side = ceil(sqrt(world area) × density) (at least kMinBoxLightmapTexels), shelf-packed
// by height; a scene that does not fit maxSize² at its density is packed again at 0.85× the density
// until it does (LightmapAtlas::density says what was used).
struct LightmapAtlas {
    uint32_t width = 0, height = 0;
    float density = 0.0f;                // texels per metre actually used
    std::vector<glm::vec4> rects;        // per Scene::nodes entry: Node::lightmapRect (zero: none)
    std::vector<glm::uvec4> texelRects;  // per node: x, y, side (texels, without the border), 0
};

// Errors name the node and its mesh when a mesh has no lightmap uvs (glTF: no TEXCOORD_1).
Result<LightmapAtlas> packLightmap(const Scene& scene, const LightmapSettings& settings);
// Writes the atlas into the scene's nodes (Node::lightmapRect).
void applyAtlas(Scene& scene, const LightmapAtlas& atlas);

// The fixed basis of a lightmap of n lobes: golden-spiral axes over the tangent-space hemisphere,
// and the sharpness of lightmapSharpness.
std::vector<glm::vec3> lightmapAxes(int lobes);
// The seed's fixed width ("not so small that gaps appear, not so wide that it over-blurs"):
// lighting::basisSharpness of the hemisphere axes (a lobe falls to half at half the mean angle to
// its neighbours) × kLightmapSharpnessScale, the scale at which the fit reconstructs irradiance best
// over skies, a window, a sun and their mix (tests/unit/test_lightmap.cpp sweeps it).
inline constexpr float kLightmapSharpnessScale = 1.4f;
float lightmapSharpness(int lobes);

// How a texel's amplitudes are fitted: non-negative least squares (lighting::fitNonNegative, Lawson
// and Hanson's active set) on two terms,
//   ‖Σ A_k G_k − L‖² over the hemisphere × radianceWeight  +  Σ_j w_j (Σ_k A_k I_k(n_j) − E(n_j))²,
// the radiance the lobes stand for (the seed's fit) and the irradiance they give — I_k(n) the
// unit lobe k's SG–cosine irradiance, exactly what the G-buffer pass evaluates — at J normals up
// to 70° from the surface normal (a normal map's range), the surface normal itself weighing as much
// as all the others (w_j). The second term is what the lightmap is
// read for; without it a delta light (a sun, a small lamp) projected onto a few wide lobes lands
// 10–40 % off in irradiance depending on where it falls between the axes. Both terms are linear in
// the radiance, so per texel the baker only accumulates the projections ∫ G_k L dω and the
// irradiances E(n_j) (Monte Carlo, delta lights exactly); the normal matrix is shared.
struct LightmapFit {
    std::vector<glm::vec3> axes;
    float sharpness = 0.0f;
    std::vector<glm::vec3> normals;  // n_j; n_0 = (0, 0, 1)
    std::vector<double> weights;     // w_j
    std::vector<double> irradiance;  // [j * N + k]: I_k(n_j)
    double radianceWeight = 0.0;
    std::vector<double> gram;  // N × N: radianceWeight ∫ G_i G_j + Σ_j I_i(n_j) I_k(n_j)
    std::vector<float> unit;   // the amplitudes of a uniform radiance of 1 over the hemisphere
    // The amplitudes from a texel's projections (N, RGB) and irradiances (J, RGB).
    std::vector<glm::vec3> solve(const std::vector<glm::dvec3>& projections,
                                 const std::vector<glm::dvec3>& irradiances) const;
};
LightmapFit lightmapFit(int lobes, float sharpness);

// The fitted radiance's irradiance at texel (x, y) for the tangent-space normal n (the SG–cosine
// product, as lib/lightmap.glsl), lux.
glm::vec3 lightmapIrradiance(const Lightmap& lightmap, uint32_t x, uint32_t y, glm::vec3 n);

struct BakeStats {
    double seconds = 0.0;
    uint64_t rays = 0;     // Embree ray casts: intersections and shadow rays
    uint32_t texels = 0;   // covered texels baked
    uint32_t covered = 0;  // covered texels of the whole atlas (= texels unless sharded)
};

// A sharded bake (rgraph bake --shard K/N): the atlas's covered texels, in row order, dealt out in
// runs of kShardRun, run r to shard r mod N, so every shard gets a like share of every part of
// the atlas. A texel's paths are seeded by the texel alone, so a shard's texels come out exactly
// as the whole bake makes them, and N merged shards are that bake bit for bit.
inline constexpr uint32_t kShardRun = 256;

struct BakeOptions {
    unsigned threads = 0;  // 0: every core
    uint32_t seed = 1;
    // Called from the baking threads' coordinator about twice a second: the fraction done and the
    // estimated seconds left.
    std::function<void(double fraction, double secondsLeft)> progress;
    // Bake only shard `shard` (0-based) of `shards`: just its texels, undilated (Lightmap::coverage
    // marks them), for mergeLightmapParts.
    uint32_t shard = 0, shards = 1;
};

// Bakes the scene's lightmap (scene.lightmap's settings, the atlas from packLightmap). Errors name
// what cannot be baked (an IES light marked baked, a light the GPU tables refuse). Lightmap::key is
// left empty (prepareLightmap sets the key it looked the cache up with).
Result<Lightmap> bakeLightmap(const Scene& scene, const LightmapAtlas& atlas,
                              const LightmapSettings& settings, const BakeOptions& options = {},
                              BakeStats* stats = nullptr);

// The content hash a lightmap is cached under: the nodes' geometry and transforms, the materials'
// diffuse albedo and emission (texture contents included), the lights, the environment (its file's
// bytes too), the bake settings and the baker's version; 16 hex digits.
std::string lightmapKey(const Scene& scene, const LightmapSettings& settings);

// The lightmap's pre-filtered specular radiance at texel i for shaded normal N and view V (tangent
// space, unit) and linear roughness: lib/lightmap.glsl's rgLightmapSpecular on the CPU (the GGX NDF
// as 3 SGs, warped to the reflection, over the radiance lobes, normalised by a uniform hemisphere).
glm::vec3 lightmapSpecular(const Lightmap& lightmap, size_t texel, glm::vec3 N, glm::vec3 V,
                           float linearRoughness);

// One EXR per scene: a layer per lobe, "sg0.R", "sg0.G", "sg0.B", ... "sg8.B" (32-bit float), and
// "coverage.Y"; the header says the basis: rgraph.lightmap.lobes, .sharpness, .axes ("x y z" per
// lobe, ';'-separated, tangent space), .unit (the amplitudes of a uniform 1-nit hemisphere), .density,
// .key, .space = "tangent".
// A part of a sharded bake carries rgraph.lightmap.shard (1-based) and .shards, .texels (its
// covered texels) and .covered (the whole atlas's) in its header; readLightmapExr refuses a part
// unless asked for one (`part`), so a part is never taken for a whole lightmap. Written to a
// temporary file beside `path` and renamed: a reader (another worker, a render) never sees half.
struct LightmapPart {
    uint32_t shard = 0, shards = 1;  // 0-based
    uint32_t texels = 0, covered = 0;
};
Result<void> writeLightmapExr(const std::string& path, const Lightmap& lightmap,
                              const LightmapPart* part = nullptr);
Result<Lightmap> readLightmapExr(const std::string& path, LightmapPart* part = nullptr);

// Fills the texels no surface covers around the covered ones (every node's border, its charts'
// gutters): each takes the mean of its filled 8-neighbours, four rings deep, so bilinear filtering
// never reads an empty texel at a chart's edge. The whole bake's last step, and the merge's.
void dilateLightmap(Lightmap& lightmap);

// Joins the parts of a sharded bake into the whole lightmap, dilated: bit-identical to baking it
// in one go. Refused, naming the file: a part of another scene or settings (key, size, basis), a
// shard given twice, a shard missing (with the ones that are), parts whose texels overlap or do not
// add up to the atlas's covered texels.
Result<Lightmap> mergeLightmapParts(const std::vector<std::string>& paths);

// The baker as a value (rg_baker's bakeLightmap): the renderer's library takes baked lightmaps from
// the cache and bakes only when its host links the baker and hands it over.
using BakeFunction = Result<Lightmap> (*)(const Scene&, const LightmapAtlas&,
                                          const LightmapSettings&, const BakeOptions&, BakeStats*);

// What a renderer calls for a scene with scene.lightmap: packs the atlas into the nodes, then reads
// <cacheDir>/<lightmapKey>.exr, or bakes it with `bake` (progress and ETA on stderr unless quiet)
// and writes it there; the result goes to scene.bakedLightmap. `rebake`: bake even when the cache
// has it. Without `bake`, a lightmap missing from the cache is an error that says how to bake it.
struct PrepareOptions {
    std::string cacheDir;
    BakeFunction bake = nullptr;
    bool quiet = false;
    bool rebake = false;
    unsigned threads = 0;         // baking threads (0: every core)
    BakeStats* stats = nullptr;   // filled when it baked
    bool* fromCache = nullptr;    // set to whether it came from the cache
    std::string* path = nullptr;  // the cache file
};
Result<void> prepareLightmap(Scene& scene, const PrepareOptions& options);

// One shard of the scene's bake (0-based `shard` of `shards`): packs the atlas into the nodes,
// then reads <cacheDir>/<key>.shard-K-of-N.exr, or bakes the shard with `options.bake` and
// writes it there; a rerun finds a finished shard, and two workers baking the same one each write
// a whole file (renamed into place). options.path/fromCache/stats are set as prepareLightmap does.
struct LightmapShard {
    Lightmap lightmap;
    LightmapPart part;
};
Result<LightmapShard> prepareLightmapShard(Scene& scene, const PrepareOptions& options,
                                           uint32_t shard, uint32_t shards);

}  // namespace rg::bake

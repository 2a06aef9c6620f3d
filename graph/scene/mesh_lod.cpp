// Levels of detail by meshoptimizer's simplifier, with errors measured against the full mesh
// through a uniform grid of triangles (nearest-triangle queries in growing shells of cells).
#include "mesh_lod.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <cmath>
#include <cstring>
#include <limits>
#include <mutex>
#include <thread>
#include <unordered_map>
#include <unistd.h>

#include <meshoptimizer.h>

#include "core/hash.h"
#include "core/temp_path.h"

namespace rg {

namespace {

constexpr float kLodRatios[] = {0.5f, 0.25f, 0.125f};
constexpr float kLodRelativeError = 0.02f;

// The squared distance from p to triangle abc: the closest point by the triangle's Voronoi regions
// (Ericson, Real-Time Collision Detection, 5.1.5).
float distanceSq(const glm::vec3& p, const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
    const glm::vec3 ab = b - a, ac = c - a, ap = p - a;
    const float d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
    auto sq = [&](const glm::vec3& q) { return glm::dot(p - q, p - q); };
    if (d1 <= 0.0f && d2 <= 0.0f) return sq(a);
    const glm::vec3 bp = p - b;
    const float d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
    if (d3 >= 0.0f && d4 <= d3) return sq(b);
    const float vc = d1 * d4 - d3 * d2;
    if (vc <= 0.0f && d1 >= 0.0f && d3 <= 0.0f) return sq(a + ab * (d1 / (d1 - d3)));
    const glm::vec3 cp = p - c;
    const float d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
    if (d6 >= 0.0f && d5 <= d6) return sq(c);
    const float vb = d5 * d2 - d1 * d6;
    if (vb <= 0.0f && d2 >= 0.0f && d6 <= 0.0f) return sq(a + ac * (d2 / (d2 - d6)));
    const float va = d3 * d6 - d5 * d4;
    if (va <= 0.0f && (d4 - d3) >= 0.0f && (d5 - d6) >= 0.0f)
        return sq(b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6))));
    const float denom = 1.0f / (va + vb + vc);
    return sq(a + ab * (vb * denom) + ac * (vc * denom));
}

// The triangles of an index list binned into a uniform grid over their bounds (each into every
// cell its box overlaps), for the distance from a point to the nearest of them.
class TriangleGrid {
public:
    TriangleGrid(const std::vector<Vertex>& v, const std::vector<uint32_t>& indices)
        : m_v(v), m_indices(indices) {
        glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
        for (uint32_t i : indices) {
            lo = glm::min(lo, v[i].position);
            hi = glm::max(hi, v[i].position);
        }
        const size_t triangles = indices.size() / 3;
        const glm::vec3 extent = glm::max(hi - lo, glm::vec3(1e-6f));
        const float side = std::clamp(std::round(2.0f * std::cbrt(float(triangles))), 1.0f, 128.0f);
        m_cell = std::max({extent.x, extent.y, extent.z}) / side;
        m_lo = lo;
        const glm::vec3 cells = glm::ceil(extent / m_cell);  // at most side + 1 each, or NaN
        for (int k = 0; k < 3; ++k)
            m_n[k] = cells[k] >= 1.0f ? int(std::min(cells[k], side + 1.0f)) : 1;
        std::vector<uint32_t> count(size_t(m_n.x) * m_n.y * m_n.z + 1, 0);
        auto each = [&](size_t t, auto&& f) {
            glm::vec3 a = v[indices[3 * t]].position, b = v[indices[3 * t + 1]].position,
                      c = v[indices[3 * t + 2]].position;
            const glm::ivec3 from = cellOf(glm::min(a, glm::min(b, c))),
                             to = cellOf(glm::max(a, glm::max(b, c)));
            for (int z = from.z; z <= to.z; ++z)
                for (int y = from.y; y <= to.y; ++y)
                    for (int x = from.x; x <= to.x; ++x) f(index({x, y, z}));
        };
        for (size_t t = 0; t < triangles; ++t) each(t, [&](size_t c) { ++count[c + 1]; });
        for (size_t c = 1; c < count.size(); ++c) count[c] += count[c - 1];
        m_start = count;
        m_items.resize(count.back());
        for (size_t t = 0; t < triangles; ++t)
            each(t, [&](size_t c) { m_items[count[c]++] = static_cast<uint32_t>(t); });
    }

    float distance(const glm::vec3& p) const {
        const glm::ivec3 c = cellOf(p);
        const int far = std::max({m_n.x, m_n.y, m_n.z});
        // How far p lies inside its cell (0 outside the grid): a triangle in no cell within r of
        // it lies at least r cells and this much away.
        const glm::vec3 inCell = p - (m_lo + glm::vec3(c) * m_cell);
        const glm::vec3 toFaces = glm::min(inCell, glm::vec3(m_cell) - inCell);
        const float inside = std::max(0.0f, std::min({toFaces.x, toFaces.y, toFaces.z}));
        float best = std::numeric_limits<float>::max();
        for (int r = 0; r <= far; ++r) {
            for (int z = c.z - r; z <= c.z + r; ++z)
                for (int y = c.y - r; y <= c.y + r; ++y)
                    for (int x = c.x - r; x <= c.x + r; ++x) {
                        // The shell of Chebyshev radius r only.
                        if (std::max({std::abs(x - c.x), std::abs(y - c.y), std::abs(z - c.z)}) !=
                            r)
                            continue;
                        if (x < 0 || y < 0 || z < 0 || x >= m_n.x || y >= m_n.y || z >= m_n.z)
                            continue;
                        const size_t cell = index({x, y, z});
                        for (uint32_t k = m_start[cell]; k < m_start[cell + 1]; ++k) {
                            const uint32_t t = m_items[k];
                            best = std::min(best, distanceSq(p, m_v[m_indices[3 * t]].position,
                                                             m_v[m_indices[3 * t + 1]].position,
                                                             m_v[m_indices[3 * t + 2]].position));
                        }
                    }
            // Every triangle not met yet lies outside the cells within r of p's (clamped) cell.
            const float bound = float(r) * m_cell + inside;
            if (best <= bound * bound) break;
        }
        return std::sqrt(best);
    }

private:
    // Clamped while still a float: a point far outside (or a NaN from an extent that overflowed
    // to infinity) must not reach the int conversion.
    glm::ivec3 cellOf(const glm::vec3& p) const {
        const glm::vec3 f = glm::floor((p - m_lo) / m_cell);
        glm::ivec3 c;
        for (int k = 0; k < 3; ++k)
            c[k] = f[k] >= 0.0f ? int(std::min(f[k], float(m_n[k] - 1))) : 0;
        return c;
    }
    size_t index(const glm::ivec3& c) const {
        return (size_t(c.z) * size_t(m_n.y) + size_t(c.y)) * size_t(m_n.x) + size_t(c.x);
    }

    const std::vector<Vertex>& m_v;
    const std::vector<uint32_t>& m_indices;
    glm::vec3 m_lo{0.0f};
    float m_cell = 1.0f;
    glm::ivec3 m_n{1};
    std::vector<uint32_t> m_start, m_items;
};

// The largest distance from the points of `from` to the surface in `grid`: its vertices (but those
// `on` says lie on that surface), and its triangles' centres — and edge midpoints with `edges`
// (where a coarse level's chords stray furthest from the full surface).
float deviation(const std::vector<Vertex>& v, const std::vector<uint32_t>& from,
                const TriangleGrid& grid, bool edges, const std::vector<bool>& on = {}) {
    float worst = 0.0f;
    std::vector<bool> seen(v.size(), false);
    for (uint32_t i : from)
        if (!seen[i]) {
            seen[i] = true;
            if (on.empty() || !on[i]) worst = std::max(worst, grid.distance(v[i].position));
        }
    for (size_t t = 0; t + 2 < from.size(); t += 3) {
        const glm::vec3 a = v[from[t]].position, b = v[from[t + 1]].position,
                        c = v[from[t + 2]].position;
        worst = std::max(worst, grid.distance((a + b + c) / 3.0f));
        if (edges)
            for (const glm::vec3& q : {(a + b) * 0.5f, (b + c) * 0.5f, (c + a) * 0.5f})
                worst = std::max(worst, grid.distance(q));
    }
    return worst;
}

std::vector<PrimitiveLod> simplify(const Primitive& p) {
    std::vector<PrimitiveLod> lods;
    const TriangleGrid full(p.vertices, p.indices);
    size_t previous = p.indices.size();
    std::vector<uint32_t> out(p.indices.size());
    for (float ratio : kLodRatios) {
        const size_t target = size_t(float(p.indices.size()) * ratio) / 3 * 3;
        float estimate = 0.0f;
        // Its own estimate held under 2 % of the mesh's extent, so that a level stays a likeness
        // (drawn a few pixels tall, not a blob); the measured error decides from how far away it
        // may be drawn.
        const size_t n =
            meshopt_simplify(out.data(), p.indices.data(), p.indices.size(),
                             &p.vertices[0].position.x, p.vertices.size(), sizeof(Vertex), target,
                             kLodRelativeError, meshopt_SimplifyLockBorder, &estimate);
        if (n < 3 || float(n) > 0.85f * float(previous)) break;
        PrimitiveLod lod;
        lod.indices.assign(out.begin(), out.begin() + static_cast<std::ptrdiff_t>(n));
        const TriangleGrid coarse(p.vertices, lod.indices);
        // The full mesh's vertices the level keeps lie on it: only the dropped ones are asked.
        std::vector<bool> kept(p.vertices.size(), false);
        for (uint32_t i : lod.indices) kept[i] = true;
        lod.error = std::max(deviation(p.vertices, p.indices, coarse, false, kept),
                             deviation(p.vertices, lod.indices, full, true));
        previous = n;
        lods.push_back(std::move(lod));
    }
    return lods;
}

// The process-wide cache: levels by content key, and the folder of their files.
struct LodCache {
    std::mutex mutex;
    std::string dir;
    std::unordered_map<uint64_t, std::vector<PrimitiveLod>> levels;
};
LodCache& lodCache() {
    static LodCache cache;
    return cache;
}

// A level file: "RGLOD1", the level count, then per level its error and its indices.
constexpr char kLodMagic[6] = {'R', 'G', 'L', 'O', 'D', '1'};

bool readLods(const std::string& file, size_t vertices, std::vector<PrimitiveLod>& out) {
    std::ifstream in(file, std::ios::binary);
    char magic[6] = {};
    uint32_t count = 0;
    if (!in.read(magic, 6) || std::memcmp(magic, kLodMagic, 6) != 0 ||
        !in.read(reinterpret_cast<char*>(&count), 4) || count > 8)
        return false;
    std::vector<PrimitiveLod> lods(count);
    for (PrimitiveLod& lod : lods) {
        uint32_t n = 0;
        if (!in.read(reinterpret_cast<char*>(&lod.error), 4) ||
            !in.read(reinterpret_cast<char*>(&n), 4) || n % 3 != 0 || n > (1u << 30))
            return false;
        lod.indices.resize(n);
        if (!in.read(reinterpret_cast<char*>(lod.indices.data()), std::streamsize(n) * 4))
            return false;
        for (uint32_t i : lod.indices)
            if (i >= vertices) return false;  // not this mesh's: ignored, built anew
    }
    out = std::move(lods);
    return true;
}

// Written to a temporary file and renamed, so a reader never sees half of one.
void writeLods(const std::string& file, const std::vector<PrimitiveLod>& lods) {
    std::error_code ec;
    std::filesystem::create_directories(std::filesystem::path(file).parent_path(), ec);
    const std::string tmp = tempPathBeside(file);
    {
        std::ofstream out(tmp, std::ios::binary);
        const uint32_t count = static_cast<uint32_t>(lods.size());
        out.write(kLodMagic, 6);
        out.write(reinterpret_cast<const char*>(&count), 4);
        for (const PrimitiveLod& lod : lods) {
            const uint32_t n = static_cast<uint32_t>(lod.indices.size());
            out.write(reinterpret_cast<const char*>(&lod.error), 4);
            out.write(reinterpret_cast<const char*>(&n), 4);
            out.write(reinterpret_cast<const char*>(lod.indices.data()), std::streamsize(n) * 4);
        }
        if (!out) {
            std::filesystem::remove(tmp, ec);
            return;
        }
    }
    std::filesystem::rename(tmp, file, ec);
    if (ec) std::filesystem::remove(tmp, ec);
}

}  // namespace

void setMeshLodCacheDir(std::string dir) {
    LodCache& cache = lodCache();
    std::lock_guard lock(cache.mutex);
    cache.dir = std::move(dir);
}

float meshDeviation(const std::vector<Vertex>& vertices, const std::vector<uint32_t>& from,
                    const std::vector<uint32_t>& to) {
    return deviation(vertices, from, TriangleGrid(vertices, to), true);
}

LodStats buildMeshLods(Scene& scene) {
    LodCache& cache = lodCache();
    std::string dir;
    {
        std::lock_guard lock(cache.mutex);
        dir = cache.dir;
    }
    const auto start = std::chrono::steady_clock::now();
    LodStats stats;
    // The primitives to simplify, after the memory cache and the files answered what they could.
    struct Work {
        Primitive* primitive;
        uint64_t key;
        std::string file;
    };
    std::vector<Work> work;
    std::vector<const Primitive*> asked;  // every primitive this call gave levels or tried to
    std::unordered_map<uint64_t, Primitive*> pending;      // work by key
    std::vector<std::pair<Primitive*, Primitive*>> twins;  // a primitive and its twin in work
    for (Mesh& mesh : scene.meshes)
        for (Primitive& p : mesh.primitives) {
            if (!p.lods.empty() || p.indices.size() / 3 < kLodMinTriangles) continue;
            asked.push_back(&p);
            ContentHash h;
            h.str("meshopt levels 1");  // what builds them: a change here makes new keys
            h.f32(kLodRelativeError);
            h.u64(p.vertices.size());
            for (const Vertex& v : p.vertices) h.bytes(&v.position, sizeof v.position);
            h.bytes(p.indices.data(), p.indices.size() * sizeof(uint32_t));
            const uint64_t key = h.value();
            {
                std::lock_guard lock(cache.mutex);
                if (auto it = cache.levels.find(key); it != cache.levels.end()) {
                    p.lods = it->second;
                    ++stats.cached;
                    continue;
                }
            }
            // Files hold only chains with a level (a mesh the simplifier cannot reduce is tried
            // again by the next process: rare, and cheap to find out).
            const std::string file = dir.empty() ? "" : dir + "/" + h.hex() + ".lod";
            if (!file.empty() && readLods(file, p.vertices.size(), p.lods)) {
                ++stats.cached;
                std::lock_guard lock(cache.mutex);
                cache.levels[key] = p.lods;
                continue;
            }
            if (auto it = pending.find(key); it != pending.end()) {
                twins.emplace_back(&p, it->second);  // the same geometry twice in this scene
                ++stats.cached;
                continue;
            }
            pending.emplace(key, &p);
            work.push_back({&p, key, file});
        }
    // Simplified and measured on every core, each primitive on its own.
    std::atomic<size_t> next{0};
    auto worker = [&] {
        for (size_t i; (i = next++) < work.size();)
            work[i].primitive->lods = simplify(*work[i].primitive);
    };
    std::vector<std::thread> threads;
    const size_t cores = std::max(1u, std::thread::hardware_concurrency());
    for (size_t t = 1; t < std::min(cores, work.size()); ++t) threads.emplace_back(worker);
    worker();
    for (std::thread& t : threads) t.join();
    for (auto& [p, twin] : twins) p->lods = twin->lods;
    for (const Work& w : work) {
        if (!w.file.empty() && !w.primitive->lods.empty()) writeLods(w.file, w.primitive->lods);
        std::lock_guard lock(cache.mutex);
        cache.levels[w.key] = w.primitive->lods;
    }
    for (const Primitive* p : asked)
        if (!p->lods.empty()) {
            ++stats.primitives;
            stats.levels += p->lods.size();
        }
    stats.ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    scene.lodStats.primitives += stats.primitives;
    scene.lodStats.levels += stats.levels;
    scene.lodStats.cached += stats.cached;
    scene.lodStats.ms += stats.ms;
    return stats;
}

}  // namespace rg

// GpuScene's geometry: every primitive's vertices and indices (its levels of detail after the
// full index list; then the mesh's points and lines) in one vertex and one index buffer, a draw
// per node and primitive with its world box (SceneDraws), a line draw per node and point or
// line primitive, and the opaque triangles' ray-cast hierarchy (SceneBvh).
#include "gpu_scene.h"

#include <algorithm>
#include <numeric>
#include <map>
#include <tuple>
#include <bit>
#include <cmath>
#include <cstring>

#include "core/hash.h"
#include "scene/bvh.h"

namespace rg::passes {

using namespace rg::gpu;

namespace {

// The world-space box around vertices under `world`.
std::pair<glm::vec3, glm::vec3> worldBox(const std::vector<Vertex>& vertices,
                                         const glm::mat4& world) {
    if (vertices.empty()) return {glm::vec3(world[3]), glm::vec3(world[3])};
    glm::vec3 lo(INFINITY), hi(-INFINITY);
    for (const Vertex& v : vertices) {
        const glm::vec3 p = glm::vec3(world * glm::vec4(v.position, 1.0f));
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    return {lo, hi};
}

}  // namespace

// A host-visible storage buffer holding `words` — one per frame slot when nodes move (updateMoving
// writes their draws' records each frame), else one for every slot.
Result<void> GpuScene::perSlot(Context& ctx, const char* name, const std::vector<glm::vec4>& words,
                               std::vector<Buffer>& out) const {
    for (uint32_t slot = 0; slot < (m_moving.empty() ? 1 : ctx.framesInFlight()); ++slot) {
        auto buf = Buffer::create(ctx, name, words.size() * sizeof(glm::vec4),
                                  VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true);
        if (!buf) return std::unexpected(buf.error());
        std::memcpy(buf->mapped(), words.data(), words.size() * sizeof(glm::vec4));
        out.push_back(std::move(*buf));
    }
    return {};
}

void GpuScene::drawFullMeshes() const {
    if (m_fullMeshes) return;
    m_fullMeshes = true;
    // Frames in flight read these buffers (the culling passes): the first switch waits for them
    // (it comes with a pipeline build, which prepares the pass that traces the scene).
    if (m_ctx) (void)m_ctx->waitIdle();
    const uint32_t full = 1;
    for (const Buffer& b : m_drawBuffers)
        std::memcpy(static_cast<uint8_t*>(b.mapped()) + sizeof(uint32_t), &full, sizeof full);
}

Result<void> GpuScene::uploadGeometry(Context& ctx) {
    std::vector<Vertex> vertices;
    std::vector<uint32_t> indices;
    struct Range {
        uint32_t firstIndex, indexCount;
        int32_t vertexOffset;
        uint32_t material;
        std::vector<DrawLod>
            lods;  // the coarser index lists after the full one, errors in the primitive's space
    };
    std::vector<std::vector<Range>> meshRanges;
    std::vector<std::vector<LineDrawItem>> meshStrokes;
    for (const Mesh& mesh : m_scene.meshes) {
        std::vector<Range> ranges;
        for (const Primitive& p : mesh.primitives) {
            ranges.push_back({static_cast<uint32_t>(indices.size()),
                              static_cast<uint32_t>(p.indices.size()),
                              static_cast<int32_t>(vertices.size()),
                              std::min<uint32_t>(
                                  p.material, static_cast<uint32_t>(m_scene.materials.size() - 1)),
                              {}});
            vertices.insert(vertices.end(), p.vertices.begin(), p.vertices.end());
            indices.insert(indices.end(), p.indices.begin(), p.indices.end());
            for (size_t l = 0; l < p.lods.size() && l + 1 < kMaxDrawLods; ++l) {
                ranges.back().lods.push_back({static_cast<uint32_t>(indices.size()),
                                              static_cast<uint32_t>(p.lods[l].indices.size()),
                                              p.lods[l].error});
                indices.insert(indices.end(), p.lods[l].indices.begin(), p.lods[l].indices.end());
            }
        }
        meshRanges.push_back(std::move(ranges));
        // Its points and lines, after its triangles.
        std::vector<LineDrawItem> strokes;
        for (const auto* list : {&mesh.lines, &mesh.points})
            for (const Primitive& p : *list) {
                if (p.indices.empty()) continue;
                strokes.push_back(
                    {static_cast<uint32_t>(indices.size()), static_cast<uint32_t>(p.indices.size()),
                     static_cast<int32_t>(vertices.size()),
                     std::min<uint32_t>(p.material,
                                        static_cast<uint32_t>(m_scene.materials.size() - 1)),
                     glm::mat4(1.0f), list == &mesh.points});
                vertices.insert(vertices.end(), p.vertices.begin(), p.vertices.end());
                indices.insert(indices.end(), p.indices.begin(), p.indices.end());
            }
        meshStrokes.push_back(std::move(strokes));
    }
    for (size_t n = 0; n < m_scene.nodes.size(); ++n) {
        const Node& node = m_scene.nodes[n];
        if (node.mesh < 0 || static_cast<size_t>(node.mesh) >= meshRanges.size()) continue;
        const auto firstDraw = static_cast<uint32_t>(m_draws.size());
        const auto firstLine = static_cast<uint32_t>(m_lineDraws.size());
        for (LineDrawItem stroke : meshStrokes[static_cast<size_t>(node.mesh)]) {
            stroke.world = node.world;
            m_lineDraws.push_back(stroke);
        }
        const glm::mat4 normal = glm::mat4(glm::transpose(glm::inverse(glm::mat3(node.world))));
        const auto& ranges = meshRanges[static_cast<size_t>(node.mesh)];
        for (size_t k = 0; k < ranges.size(); ++k)
            if (ranges[k].indexCount) {
                const auto [lo, hi] =
                    worldBox(m_scene.meshes[static_cast<size_t>(node.mesh)].primitives[k].vertices,
                             node.world);
                DrawItem& item = m_draws.emplace_back(
                    DrawItem{ranges[k].firstIndex, ranges[k].indexCount, ranges[k].vertexOffset,
                             ranges[k].material, node.world, normal, lo, hi, node.lightmapRect});
                item.lods[0] = {item.firstIndex, item.indexCount, 0.0f};
                item.castsShadows = node.castShadows &&
                                    m_scene.materials[item.material].alphaMode != AlphaMode::Blend;
                // An error in the primitive's space, in the world: times the node's largest axis scale.
                const float scale = std::max({glm::length(glm::vec3(node.world[0])),
                                              glm::length(glm::vec3(node.world[1])),
                                              glm::length(glm::vec3(node.world[2]))});
                if (m_levelsOfDetail)
                    for (const DrawLod& lod : ranges[k].lods)
                        item.lods[item.lodCount++] = {lod.firstIndex, lod.indexCount,
                                                      lod.error * scale};
            }
        if (node.dynamic) addMoving(n, firstDraw, firstLine);
    }
    m_drawCull.resize(m_draws.size());
    for (size_t d = 0; d < m_draws.size(); ++d) {
        const DrawItem& item = m_draws[d];
        DrawCull& c = m_drawCull[d];
        c.lo = item.boundsMin;
        c.hi = item.boundsMax;
        c.lodCount = item.lodCount;
        for (uint32_t l = 1; l < item.lodCount; ++l) c.error[l - 1] = item.lods[l].error;
    }
    // The camera's batches: the same mesh (vertex offset, full index range) and material,
    // ordered by their camera run (CameraRun: pipeline material, alpha mode, cull mode, texture
    // set, window of materials), then material, then first draw, so that a run's batches are
    // consecutive: its indirect commands one range for the GPU-culled G-buffer (RgDraw's
    // `camera`).
    std::vector<glm::uvec4> cameraWord(m_draws.size(), glm::uvec4(0));
    {
        std::map<std::tuple<int32_t, uint32_t, uint32_t, uint32_t>, uint32_t> batchOf;
        std::vector<std::vector<uint32_t>> members;  // per batch in draw order: its draws
        for (size_t d = 0; d < m_draws.size(); ++d) {
            const DrawItem& item = m_draws[d];
            auto [at, added] = batchOf.emplace(
                std::tuple(item.vertexOffset, item.firstIndex, item.indexCount, item.material),
                static_cast<uint32_t>(members.size()));
            if (added) members.emplace_back();
            members[at->second].push_back(static_cast<uint32_t>(d));
        }
        // The runs' keys, numbered in key order.
        using RunKey = std::tuple<std::string, int, bool, uint32_t, uint32_t>;
        auto runKey = [&](uint32_t material) {
            const Material& m = m_scene.materials[material];
            return RunKey(m.model, static_cast<int>(m.alphaMode), m.doubleSided,
                          m_materialTextureSet[material], material / m_materialWindow);
        };
        std::map<RunKey, uint32_t> runOf;
        for (const auto& draws : members) runOf.emplace(runKey(m_draws[draws.front()].material), 0);
        m_cameraRuns.clear();
        for (auto& [key, run] : runOf) {
            run = static_cast<uint32_t>(m_cameraRuns.size());
            m_cameraRuns.push_back(
                {0, 0, std::get<3>(key), std::get<4>(key) * m_materialWindow, std::get<2>(key)});
        }
        std::vector<uint32_t> batchRun(members.size());
        for (size_t b = 0; b < members.size(); ++b)
            batchRun[b] = runOf.at(runKey(m_draws[members[b].front()].material));
        std::vector<uint32_t> order(members.size());
        std::iota(order.begin(), order.end(), 0u);
        std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
            return std::pair(batchRun[a], m_draws[members[a].front()].material) <
                   std::pair(batchRun[b], m_draws[members[b].front()].material);
        });
        m_cameraBatch.resize(m_draws.size());
        m_drawRun.resize(m_draws.size());
        uint32_t slot = 0;
        for (uint32_t b = 0; b < order.size(); ++b) {
            const std::vector<uint32_t>& draws = members[order[b]];
            const uint32_t material = m_draws[draws.front()].material;
            CameraRun& run = m_cameraRuns[batchRun[order[b]]];
            if (run.commands == 0) run.firstCommand = b * kMaxDrawLods;
            run.commands += kMaxDrawLods;
            const bool gbuffer = m_scene.materials[material].alphaMode != AlphaMode::Blend;
            for (uint32_t d : draws) {
                m_cameraBatch[d] = b;
                m_drawRun[d] = batchRun[order[b]];
                if (gbuffer)
                    cameraWord[d] = glm::uvec4(b + 1, slot, static_cast<uint32_t>(draws.size()),
                                               b * kMaxDrawLods - run.firstCommand);
            }
            slot += static_cast<uint32_t>(draws.size());
        }
        m_cameraBatchCount = static_cast<uint32_t>(members.size());
    }
    // The casters' batches: the same mesh (vertex offset, full index range) and cull mode, in draw
    // order; each batch's instance slots follow the batches before it (RgDraw's `shadow`).
    std::vector<glm::uvec4> shadowWord(m_draws.size(), glm::uvec4(0));
    {
        std::map<std::tuple<int32_t, uint32_t, uint32_t, bool>, uint32_t> batchOf;
        for (size_t d = 0; d < m_draws.size(); ++d) {
            const DrawItem& item = m_draws[d];
            if (!item.castsShadows) continue;
            const bool doubleSided = m_scene.materials[item.material].doubleSided;
            auto [at, added] = batchOf.emplace(
                std::tuple(item.vertexOffset, item.firstIndex, item.indexCount, doubleSided),
                static_cast<uint32_t>(m_shadowBatches.size()));
            if (added) m_shadowBatches.push_back({{}, doubleSided});
            m_shadowBatches[at->second].draws.push_back(static_cast<uint32_t>(d));
        }
        uint32_t slot = 0;
        for (size_t b = 0; b < m_shadowBatches.size(); ++b) {
            const auto members = static_cast<uint32_t>(m_shadowBatches[b].draws.size());
            for (uint32_t d : m_shadowBatches[b].draws)
                shadowWord[d] = glm::uvec4(static_cast<uint32_t>(b) + 1, slot, members, 0);
            slot += members;
        }
    }
    // SceneDraws: a uvec4 header (draw count), then per draw (boxMin, firstIndex), (boxMax,
    // indexCount), (vertexOffset, camera run, casts shadows, level-of-detail count), the levels'
    // first indices, index counts and errors, then its shadow and camera batches (lib/scene.glsl
    // RgDraw) — 128 bytes.
    {
        constexpr size_t kWords = kDrawWords;
        std::vector<glm::vec4> words(1 + kWords * std::max<size_t>(m_draws.size(), 1),
                                     glm::vec4(0.0f));
        words[0] = glm::vec4(std::bit_cast<float>(static_cast<uint32_t>(m_draws.size())), 0.0f,
                             0.0f, 0.0f);
        for (size_t d = 0; d < m_draws.size(); ++d) {
            const DrawItem& item = m_draws[d];
            glm::vec4* w = &words[1 + kWords * d];
            w[0] = glm::vec4(item.boundsMin, std::bit_cast<float>(item.firstIndex));
            w[1] = glm::vec4(item.boundsMax, std::bit_cast<float>(item.indexCount));
            w[2] = glm::vec4(std::bit_cast<float>(item.vertexOffset),
                             std::bit_cast<float>(m_drawRun[d]),
                             std::bit_cast<float>(item.castsShadows ? 1u : 0u),
                             std::bit_cast<float>(item.lodCount));
            for (uint32_t l = 0; l < kMaxDrawLods; ++l) {
                w[3][static_cast<int>(l)] = std::bit_cast<float>(item.lods[l].firstIndex);
                w[4][static_cast<int>(l)] = std::bit_cast<float>(item.lods[l].indexCount);
                w[5][static_cast<int>(l)] = item.lods[l].error;
            }
            for (int k = 0; k < 4; ++k) {
                w[6][k] = std::bit_cast<float>(shadowWord[d][k]);
                w[7][k] = std::bit_cast<float>(cameraWord[d][k]);
            }
        }
        if (auto r = perSlot(ctx, "scene.draws", words, m_drawBuffers); !r) return r;
        m_staticHash.bytes(words.data(), words.size() * sizeof(glm::vec4));
        for (const DrawItem& item : m_draws) {
            m_staticHash.bytes(&item.world, sizeof item.world);
            m_staticHash.u64(item.material);  // SceneDraws holds its run, not its material
        }
        for (const LineDrawItem& item : m_lineDraws) {
            const uint32_t words[] = {item.firstIndex, item.indexCount,
                                      static_cast<uint32_t>(item.vertexOffset), item.material,
                                      item.points ? 1u : 0u};
            m_staticHash.bytes(words, sizeof words);
            m_staticHash.bytes(&item.world, sizeof item.world);
        }
    }
    // SceneTransforms: per draw what scene.vert's push constants hold for a single draw, then the
    // last frame's world matrix (the same for a draw that does not move): kTransformWords vec4.
    {
        std::vector<glm::vec4> t(kTransformWords * std::max<size_t>(m_draws.size(), 1),
                                 glm::vec4(0.0f));
        for (size_t d = 0; d < m_draws.size(); ++d)
            writeTransform(&t[kTransformWords * d], d, m_draws[d].world);
        if (auto r = perSlot(ctx, "scene.transforms", t, m_transforms); !r) return r;
    }
    if (vertices.empty()) {  // keep valid (empty) buffers for an empty scene
        vertices.resize(1);
        indices.resize(3, 0);
    }
    auto upload = [&](Buffer& target, const void* data, size_t bytes, VkBufferUsageFlags usage,
                      const char* name) -> Result<void> {
        auto staging = Buffer::create(ctx, std::string(name) + ".staging", bytes,
                                      VK_BUFFER_USAGE_TRANSFER_SRC_BIT, true);
        if (!staging) return std::unexpected(staging.error());
        std::memcpy(staging->mapped(), data, bytes);
        auto buf =
            Buffer::create(ctx, name, bytes, usage | VK_BUFFER_USAGE_TRANSFER_DST_BIT, false);
        if (!buf) return std::unexpected(buf.error());
        target = std::move(*buf);
        VkBuffer src = staging->buffer(), dst = target.buffer();
        return ctx.submitNow([&](VkCommandBuffer cmd) {
            VkBufferCopy region{0, 0, bytes};
            vkCmdCopyBuffer(cmd, src, dst, 1, &region);
            memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                          VK_PIPELINE_STAGE_2_VERTEX_INPUT_BIT,
                          VK_ACCESS_2_VERTEX_ATTRIBUTE_READ_BIT | VK_ACCESS_2_INDEX_READ_BIT);
        });
    };
    m_staticHash.bytes(vertices.data(), vertices.size() * sizeof(Vertex));
    m_staticHash.bytes(indices.data(), indices.size() * sizeof(uint32_t));
    if (auto r = upload(m_vertices, vertices.data(), vertices.size() * sizeof(Vertex),
                        VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, "scene.vertices");
        !r)
        return r;
    return upload(m_indices, indices.data(), indices.size() * sizeof(uint32_t),
                  VK_BUFFER_USAGE_INDEX_BUFFER_BIT, "scene.indices");
}

GpuScene::Memory GpuScene::memory() const {
    Memory m;
    m.geometry = m_vertices.size() + m_indices.size() + m_bvh.size();
    for (const auto* list : {&m_drawBuffers, &m_transforms})
        for (const Buffer& b : *list) m.geometry += b.size();
    auto bytes = [&](const gpu::Image& image) -> uint64_t {
        return image ? gpu::Image::requirements(*m_ctx, image.desc()).size : 0;
    };
    for (const gpu::Image& image : m_textureArrays) m.textures += bytes(image);
    m.textures += bytes(m_white) + bytes(m_flatNormal);
    m.environment = bytes(m_environment);
    m.lightmap = bytes(m_lightmap);
    return m;
}

VkBuffer GpuScene::bvhBuffer() const {
    auto buffer = makeBvhBuffer();
    return buffer ? *buffer : VK_NULL_HANDLE;  // ShaderProgram reports it (makeBindingBuffer)
}

Result<VkBuffer> GpuScene::makeBvhBuffer() const {
    if (m_bvh.buffer() != VK_NULL_HANDLE) return m_bvh.buffer();
    std::vector<glm::vec3> corners;
    // The draws' triangles, from the scene's meshes under each node's transform.
    for (const Node& node : m_scene.nodes) {
        if (node.mesh < 0 || static_cast<size_t>(node.mesh) >= m_scene.meshes.size()) continue;
        if (node.lightShape) continue;  // an area light's shape: its own rays must not find it
        if (node.dynamic) continue;     // it moves: the hierarchy, built once, would keep it behind
        for (const Primitive& p : m_scene.meshes[static_cast<size_t>(node.mesh)].primitives) {
            const uint32_t material =
                std::min<uint32_t>(p.material, static_cast<uint32_t>(m_scene.materials.size() - 1));
            if (m_scene.materials[material].alphaMode == AlphaMode::Blend) continue;
            for (size_t i = 0; i + 2 < p.indices.size(); i += 3)
                for (int k = 0; k < 3; ++k) {
                    const uint32_t v = p.indices[i + k];
                    corners.push_back(
                        v < p.vertices.size()
                            ? glm::vec3(node.world * glm::vec4(p.vertices[v].position, 1.0f))
                            : glm::vec3(0.0f));
                }
        }
    }
    const FlatBvh bvh = buildBvh(corners);
    const glm::uvec4 header(bvh.nodeCount, bvh.triangleCount, bvh.depth, 0u);
    const size_t bytes = sizeof header + std::max<size_t>(bvh.data.size(), 1) * sizeof(glm::vec4);
    auto buf = Buffer::create(*m_ctx, "scene.bvh", bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true);
    if (!buf) return std::unexpected(buf.error());
    auto* p = static_cast<uint8_t*>(buf->mapped());
    std::memset(p, 0, bytes);
    std::memcpy(p, &header, sizeof header);
    if (!bvh.data.empty())
        std::memcpy(p + sizeof header, bvh.data.data(), bvh.data.size() * sizeof(glm::vec4));
    m_bvh = std::move(*buf);
    return m_bvh.buffer();
}

}  // namespace rg::passes

// GpuScene's moving nodes (Node::dynamic): placed each frame at the frame's time along their
// paths, or where the library put them, with their draws' transforms, boxes and levels of detail;
// each draw keeps its last frame's world matrix in SceneTransforms for the motion the G-buffer and
// forward passes write (shaders/passes/scene.vert with RG_MOTION).
#include <algorithm>
#include <cmath>
#include <cstring>

#include "gpu_scene.h"

#include <bit>

namespace rg::passes {

void GpuScene::writeTransform(glm::vec4* out, size_t d, const glm::mat4& previous) const {
    const DrawItem& item = m_draws[d];
    for (int c = 0; c < 4; ++c) out[c] = item.world[c];
    for (int c = 0; c < 3; ++c) out[4 + c] = item.normalMatrix[c];
    // scene.vert: the material's index in its window (lib/material.glsl's RG_MATERIAL_WINDOW).
    out[4].w = std::bit_cast<float>(item.material % m_materialWindow);
    out[7] = item.lightmapRect;
    for (int c = 0; c < 4; ++c) out[8 + c] = previous[c];
}

void GpuScene::addMoving(size_t node, uint32_t firstDraw, uint32_t firstLine) {
    const Node& n = m_scene.nodes[node];
    Moving m;
    m.node = node;
    m.firstDraw = firstDraw;
    m.drawCount = static_cast<uint32_t>(m_draws.size()) - firstDraw;
    m.firstLine = firstLine;
    m.lineCount = static_cast<uint32_t>(m_lineDraws.size()) - firstLine;
    // Each draw's box in the mesh's own space (the draws follow the mesh's primitives with an
    // index range, in order).
    for (const Primitive& p : m_scene.meshes[static_cast<size_t>(n.mesh)].primitives) {
        if (p.indices.empty()) continue;
        glm::vec3 lo(INFINITY), hi(-INFINITY);
        for (const Vertex& v : p.vertices)
            lo = glm::min(lo, v.position), hi = glm::max(hi, v.position);
        if (p.vertices.empty()) lo = hi = glm::vec3(0.0f);
        m.boxes.emplace_back(lo, hi);
        // Its coarser levels' errors in the mesh's space: scaled by the node's scale each frame.
        std::array<float, kMaxDrawLods - 1> errors{};
        for (size_t l = 0; l < p.lods.size() && l + 1 < kMaxDrawLods; ++l)
            errors[l] = p.lods[l].error;
        m.lodErrors.push_back(errors);
    }
    m_drawMoves.resize(m_draws.size(), 0);
    std::fill(m_drawMoves.begin() + firstDraw, m_drawMoves.end(), uint8_t(1));
    m_moving.push_back(std::move(m));
}

Result<void> GpuScene::setNodeTransform(const std::string& name, const glm::mat4& world) {
    for (Moving& m : m_moving)
        if (m_scene.nodes[m.node].name == name) {
            m.placed = world;
            return {};
        }
    const auto node = std::find_if(m_scene.nodes.begin(), m_scene.nodes.end(),
                                   [&](const Node& n) { return n.name == name; });
    if (node == m_scene.nodes.end())
        return fail(ErrorCode::NotFound, "the scene has no node '" + name + "'");
    if (node->dynamic)
        return fail(ErrorCode::InvalidInput,
                    "node '" + name + "' draws no triangles: nothing of it moves on screen");
    return fail(ErrorCode::InvalidInput,
                "node '" + name +
                    "' was declared static: only a dynamic node moves after the scene loads "
                    "(Mesh::dynamic, or a `path` in a Lua scene)");
}

void GpuScene::updateMoving(uint32_t slot, bool fresh) {
    if (m_moving.empty()) return;
    auto* transforms = static_cast<glm::vec4*>(m_transforms[slot].mapped());
    auto* words = static_cast<glm::vec4*>(m_drawBuffers[slot].mapped());
    m_nodesMoved = false;
    m_movingMin = glm::vec3(INFINITY);
    m_movingMax = glm::vec3(-INFINITY);
    for (const Moving& m : m_moving) {
        const Node& node = m_scene.nodes[m.node];
        const glm::mat4 world = m.placed ? *m.placed : node.at(m_time);
        const glm::mat4 normal = glm::mat4(glm::transpose(glm::inverse(glm::mat3(world))));
        // A level's error in the world: times the node's largest axis scale (as at load).
        const float scale =
            std::max({glm::length(glm::vec3(world[0])), glm::length(glm::vec3(world[1])),
                      glm::length(glm::vec3(world[2]))});
        for (uint32_t k = 0; k < m.drawCount; ++k) {
            const size_t d = m.firstDraw + k;
            DrawItem& item = m_draws[d];
            const glm::mat4 previous = fresh ? world : item.world;
            m_nodesMoved = m_nodesMoved || previous != world;
            item.world = world;
            item.normalMatrix = normal;
            // The mesh-space box's corners under the transform: a box around the draw.
            const auto [lo, hi] = m.boxes[k];
            glm::vec3 wlo(INFINITY), whi(-INFINITY);
            for (int c = 0; c < 8; ++c) {
                const glm::vec3 corner((c & 1) ? hi.x : lo.x, (c & 2) ? hi.y : lo.y,
                                       (c & 4) ? hi.z : lo.z);
                const glm::vec3 p = glm::vec3(world * glm::vec4(corner, 1.0f));
                wlo = glm::min(wlo, p), whi = glm::max(whi, p);
            }
            item.boundsMin = m_drawCull[d].lo = wlo;
            item.boundsMax = m_drawCull[d].hi = whi;
            for (uint32_t l = 1; l < item.lodCount; ++l)
                item.lods[l].error = m_drawCull[d].error[l - 1] = m.lodErrors[k][l - 1] * scale;
            m_movingMin = glm::min(m_movingMin, wlo);
            m_movingMax = glm::max(m_movingMax, whi);
            writeTransform(transforms + kTransformWords * d, d, previous);
            // SceneDraws (lib/scene.glsl RgDraw): the box's corners, their w words kept, and the
            // levels' errors at the node's scale now (the GPU's level choices read them).
            glm::vec4* w = words + 1 + kDrawWords * d;
            w[0] = glm::vec4(wlo, w[0].w);
            w[1] = glm::vec4(whi, w[1].w);
            for (uint32_t l = 1; l < item.lodCount; ++l)
                w[5][static_cast<int>(l)] = item.lods[l].error;
        }
        for (uint32_t k = 0; k < m.lineCount; ++k) m_lineDraws[m.firstLine + k].world = world;
    }
}

}  // namespace rg::passes

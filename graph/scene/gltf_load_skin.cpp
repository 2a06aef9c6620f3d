// glTF morph targets and skins, applied once at load (animations move nodes, not weights or joints:
// gltf_load_animation.cpp): a mesh at its default weights (a node's own weights give that node a
// copy at those), a skinned mesh in the pose its joints' nodes give (glTF 2.0 §3.7.2.2 and
// §3.7.3).
#include <algorithm>
#include <cmath>

#include <glm/gtc/type_ptr.hpp>

#include "gltf_load_detail.h"
#include "scene_detail.h"
#include "tinygltf.h"

namespace rg::gltf_load {

using namespace scene_detail;

namespace {
constexpr size_t kMaxTargets = 256;  // morph targets per primitive
}  // namespace

Result<void> Loader::morphWeights(size_t m, const std::vector<double>& weights,
                                  const std::string& where) {
    const auto& prims = model.meshes[m].primitives;
    const size_t targets = prims.empty() ? 0 : prims[0].targets.size();
    for (size_t p = 0; p < prims.size(); ++p) {
        if (prims[p].targets.size() != targets)
            return error(ErrorCode::InvalidInput,
                         named("mesh", m, model.meshes[m].name) + " primitive " +
                             std::to_string(p) + ": " + std::to_string(prims[p].targets.size()) +
                             " morph targets, primitive 0 has " + std::to_string(targets) +
                             " (glTF: every primitive of a mesh has as many)");
    }
    if (targets > kMaxTargets)
        return error(ErrorCode::InvalidInput,
                     named("mesh", m, model.meshes[m].name) + ": " + std::to_string(targets) +
                         " morph targets (at most " + std::to_string(kMaxTargets) + ")");
    if (!weights.empty() && weights.size() != targets)
        return error(ErrorCode::InvalidInput, where + " has " + std::to_string(weights.size()) +
                                                  " values, the mesh " + std::to_string(targets) +
                                                  " morph targets");
    for (size_t i = 0; i < weights.size(); ++i)
        if (!std::isfinite(weights[i]))
            return error(ErrorCode::InvalidInput,
                         where + "[" + std::to_string(i) + "] is not a finite number");
    return {};
}

// §3.7.2.2: each target's POSITION, NORMAL and TANGENT (xyz) displacements, times its weight,
// added to the base attributes; targets on other attributes are named and left out.
Result<void> Loader::morph(const std::string& where, const tinygltf::Primitive& prim,
                           const std::vector<double>& weights, Primitive& p, bool normals,
                           bool tangents) {
    const size_t n = p.vertices.size();
    for (size_t t = 0; t < prim.targets.size(); ++t) {
        const float w = t < weights.size() ? float(weights[t]) : 0.0f;
        const std::string at = where + ": targets[" + std::to_string(t) + "]";
        for (const auto& [semantic, index] : prim.targets[t]) {
            const bool position = semantic == "POSITION", normal = semantic == "NORMAL",
                       tangent = semantic == "TANGENT";
            if (!position && !normal && !tangent) {
                if (w != 0.0f)
                    warn(at + ": a morph target of " + semantic +
                         " is not applied (rgraph morphs POSITION, NORMAL and TANGENT)");
                continue;
            }
            auto d = readFloats(at, semantic, index, TINYGLTF_TYPE_VEC3);
            if (!d) return std::unexpected(d.error());
            if (d->size() / 3 != n)
                return error(ErrorCode::InvalidInput,
                             at + ": " + semantic + ": accessor " + std::to_string(index) +
                                 " has " + std::to_string(d->size() / 3) +
                                 " elements, POSITION has " + std::to_string(n));
            if (w == 0.0f || (normal && !normals) || (tangent && !tangents)) continue;
            for (size_t i = 0; i < n; ++i) {
                const glm::vec3 delta = w * glm::make_vec3(&(*d)[3 * i]);
                Vertex& v = p.vertices[i];
                if (position) v.position += delta;
                if (normal) v.normal += delta;
                if (tangent) v.tangent += glm::vec4(delta, 0.0f);
            }
        }
    }
    if (tangents && !prim.targets.empty())
        for (Vertex& v : p.vertices) {
            const float len = glm::length(glm::vec3(v.tangent));
            if (len > 0.0f) v.tangent = glm::vec4(glm::vec3(v.tangent) / len, v.tangent.w);
        }
    return {};
}

Result<void> Loader::copying(const Mesh& mesh, const std::string& where) {
    for (const auto* list : {&mesh.primitives, &mesh.lines, &mesh.points})
        for (const auto& p : *list) copiedVertices += p.vertices.size();
    if (copiedVertices > kMaxCopiedVertices)
        return error(ErrorCode::InvalidInput,
                     where + ": the meshes copied for morph weights and skins of nodes reach " +
                         std::to_string(copiedVertices) + " vertices (at most " +
                         std::to_string(kMaxCopiedVertices) + ")");
    return {};
}

// A node's weights replace its mesh's (§3.7.2.2): a node with weights of its own draws a copy of
// the mesh morphed by them, one copy per distinct set of weights.
Result<int32_t> Loader::nodeMesh(size_t nodeIndex) {
    const auto& n = model.nodes[nodeIndex];
    const size_t m = size_t(n.mesh);
    if (n.weights.empty() || n.weights == model.meshes[m].weights) return n.mesh;
    if (auto r = morphWeights(m, n.weights, named("node", nodeIndex, n.name) + ": weights"); !r)
        return std::unexpected(r.error());
    const auto key = std::make_pair(n.mesh, n.weights);
    if (auto it = morphed.find(key); it != morphed.end()) return it->second;
    auto mesh = this->mesh(m, n.weights);
    if (!mesh) return std::unexpected(mesh.error());
    if (auto r = copying(*mesh, named("node", nodeIndex, n.name)); !r)
        return std::unexpected(r.error());
    const auto index = static_cast<int32_t>(scene.meshes.size());
    scene.meshes.push_back(std::move(*mesh));
    morphed[key] = index;
    return index;
}

// A node's world transform, for a joint the scene's walk did not reach: its parents' chain.
Result<glm::mat4> Loader::worldOf(size_t node) {
    if (worlds[node]) return *worlds[node];
    if (parents.empty()) {
        parents.assign(model.nodes.size(), -1);
        for (size_t i = 0; i < model.nodes.size(); ++i)
            for (int c : model.nodes[i].children)
                if (c >= 0 && size_t(c) < parents.size()) parents[size_t(c)] = int(i);
    }
    std::vector<size_t> chain{node};
    while (parents[chain.back()] >= 0 && !worlds[size_t(parents[chain.back()])]) {
        if (chain.size() > model.nodes.size())
            return error(ErrorCode::InvalidInput, named("node", node, model.nodes[node].name) +
                                                      ": its ancestors form a cycle");
        chain.push_back(size_t(parents[chain.back()]));
    }
    const int top = parents[chain.back()];
    glm::mat4 world = top >= 0 ? *worlds[size_t(top)] : glm::mat4(1.0f);
    for (auto it = chain.rbegin(); it != chain.rend(); ++it) {
        auto local = localTransform(*it);
        if (!local) return std::unexpected(local.error());
        world = world * *local;
        worlds[*it] = world;
    }
    return world;
}

// §3.7.3: a skinned vertex is Σ weight_k · (world(joint_k) · inverseBindMatrix_k) · vertex; the
// skinned node's own transform does not apply. Each skinned node gets the posed copy of its mesh
// in world space. Weights are renormalised (exporters leave rounding in them); a vertex with
// none stays where the node's transform puts it.
Result<void> Loader::skins() {
    for (const SkinnedNode& s : skinned) {
        const auto& n = model.nodes[s.node];
        const std::string where = named("node", s.node, n.name);
        if (size_t(n.skin) >= model.skins.size())
            return error(ErrorCode::InvalidInput,
                         where + ": skin " + std::to_string(n.skin) + " does not exist (" +
                             std::to_string(model.skins.size()) + " skins)");
        const auto& skin = model.skins[size_t(n.skin)];
        const std::string sw = named("skin", size_t(n.skin), skin.name);
        if (skin.joints.empty()) return error(ErrorCode::InvalidInput, sw + ": no joints");
        std::vector<float> inverseBind;
        if (skin.inverseBindMatrices >= 0) {
            RG_TRY(inverseBind, readFloats(sw, "inverseBindMatrices", skin.inverseBindMatrices,
                                           TINYGLTF_TYPE_MAT4));
            if (inverseBind.size() / 16 != skin.joints.size())
                return error(ErrorCode::InvalidInput, sw + ": inverseBindMatrices has " +
                                                          std::to_string(inverseBind.size() / 16) +
                                                          " matrices, joints " +
                                                          std::to_string(skin.joints.size()));
        }
        std::vector<glm::mat4> joint(skin.joints.size());
        for (size_t k = 0; k < skin.joints.size(); ++k) {
            const int j = skin.joints[k];
            if (j < 0 || size_t(j) >= model.nodes.size())
                return error(ErrorCode::InvalidInput, sw + ": joints[" + std::to_string(k) +
                                                          "] is node " + std::to_string(j) +
                                                          ", which does not exist");
            glm::mat4 world;
            RG_TRY(world, worldOf(size_t(j)));
            joint[k] = inverseBind.empty() ? world : world * glm::make_mat4(&inverseBind[16 * k]);
        }
        const int32_t source = scene.nodes[s.sceneNode].mesh;
        const glm::mat4 nodeWorld = scene.nodes[s.sceneNode].world;
        if (auto r = copying(scene.meshes[size_t(source)], where); !r) return r;
        Mesh posed = scene.meshes[size_t(source)];
        // Its triangles, lines and points, in meshSkinning's order.
        std::vector<Primitive*> parts;
        for (auto* list : {&posed.primitives, &posed.lines, &posed.points})
            for (Primitive& prim : *list) parts.push_back(&prim);
        for (size_t p = 0; p < parts.size(); ++p) {
            const Skinning& sk = meshSkinning[size_t(source)][p];
            if (sk.influences == 0)
                warn(where + ": primitive " + std::to_string(p) +
                     " has no JOINTS_0/WEIGHTS_0; drawn with the node's transform");
            auto& vertices = parts[p]->vertices;
            for (size_t i = 0; i < vertices.size(); ++i) {
                glm::mat4 m(0.0f);
                float sum = 0.0f;
                for (size_t k = 0; k < sk.influences; ++k) {
                    const float w = sk.weights[i * sk.influences + k];
                    if (w == 0.0f) continue;
                    const uint32_t j = sk.joints[i * sk.influences + k];
                    if (j >= joint.size())
                        return error(ErrorCode::InvalidInput,
                                     where + ": primitive " + std::to_string(p) + " vertex " +
                                         std::to_string(i) + " names joint " + std::to_string(j) +
                                         ", " + sw + " has " + std::to_string(joint.size()));
                    m += w * joint[j];
                    sum += w;
                }
                m = sum > 0.0f ? m / sum : nodeWorld;
                Vertex& v = vertices[i];
                const glm::mat3 linear(m);
                v.position = glm::vec3(m * glm::vec4(v.position, 1.0f));
                const glm::vec3 nrm = glm::transpose(glm::inverse(linear)) * v.normal;
                const glm::vec3 tan = linear * glm::vec3(v.tangent);
                if (glm::length(nrm) > 0.0f) v.normal = glm::normalize(nrm);
                if (glm::length(tan) > 0.0f)
                    v.tangent = glm::vec4(glm::normalize(tan), v.tangent.w);
            }
            if (sk.flatNormals) generateFlatNormals(*parts[p]);
            if (sk.generatedTangents) {  // from the normal map's uv set, as primitive() did
                const uint32_t m = parts[p]->material;
                generateTangents(*parts[p],
                                 m < scene.materials.size()
                                     ? std::min(scene.materials[m].normalTex.texCoord, 1u)
                                     : 0u);
            }
        }
        scene.nodes[s.sceneNode].mesh = static_cast<int32_t>(scene.meshes.size());
        scene.nodes[s.sceneNode].world = glm::mat4(1.0f);
        scene.meshes.push_back(std::move(posed));
        meshSkinning.emplace_back();
    }
    return {};
}

}  // namespace rg::gltf_load

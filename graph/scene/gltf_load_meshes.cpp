// glTF meshes -> Scene meshes: each primitive's attributes and indices read through the checked
// accessors, strips and fans made lists, missing normals and tangents generated.
#include <algorithm>
#include <cmath>

#include "gltf_load_detail.h"
#include "scene_detail.h"
#include "tinygltf.h"

namespace rg {

using namespace scene_detail;

namespace gltf_load {

namespace {

const char* modeName(int mode) {
    switch (mode) {
        case TINYGLTF_MODE_POINTS:
            return "POINTS";
        case TINYGLTF_MODE_LINE:
            return "LINES";
        case TINYGLTF_MODE_LINE_LOOP:
            return "LINE_LOOP";
        case TINYGLTF_MODE_LINE_STRIP:
            return "LINE_STRIP";
        case TINYGLTF_MODE_TRIANGLES:
            return "TRIANGLES";
        case TINYGLTF_MODE_TRIANGLE_STRIP:
            return "TRIANGLE_STRIP";
        case TINYGLTF_MODE_TRIANGLE_FAN:
            return "TRIANGLE_FAN";
        default:
            return nullptr;
    }
}

}  // namespace

// KHR_materials_variants: the root's list of variant names; options.variant picks one.
Result<void> Loader::chooseVariant() {
    if (options.variant.empty()) return {};
    std::vector<std::string> names;
    if (auto it = model.extensions.find("KHR_materials_variants"); it != model.extensions.end()) {
        const tinygltf::Value& list = it->second.Get("variants");
        for (size_t i = 0; list.IsArray() && i < list.ArrayLen(); ++i) {
            const tinygltf::Value& name = list.Get(int(i)).Get("name");
            names.push_back(name.IsString() ? name.Get<std::string>() : "");
        }
    }
    for (size_t i = 0; i < names.size(); ++i)
        if (names[i] == options.variant) {
            variant = int(i);
            return {};
        }
    std::string all;
    for (const auto& n : names) all += (all.empty() ? "'" : ", '") + n + "'";
    return error(ErrorCode::InvalidInput,
                 "material variant '" + options.variant + "' is not in the file (" +
                     (names.empty() ? std::string("it declares no KHR_materials_variants")
                                    : "its variants: " + all) +
                     ")");
}

Result<int> Loader::variantMaterial(const std::string& where, const tinygltf::Primitive& prim) {
    if (variant < 0) return prim.material;
    auto it = prim.extensions.find("KHR_materials_variants");
    if (it == prim.extensions.end()) return prim.material;
    const tinygltf::Value& mappings = it->second.Get("mappings");
    if (!mappings.IsArray())
        return error(ErrorCode::InvalidInput,
                     where + ": KHR_materials_variants.mappings: expected an array");
    for (size_t i = 0; i < mappings.ArrayLen(); ++i) {
        const tinygltf::Value& m = mappings.Get(int(i));
        const tinygltf::Value& variants = m.Get("variants");
        for (size_t k = 0; variants.IsArray() && k < variants.ArrayLen(); ++k)
            if (indexOf(variants.Get(int(k))) == variant) {
                const int material = indexOf(m.Get("material"));
                if (material < 0)
                    return error(ErrorCode::InvalidInput,
                                 where + ": KHR_materials_variants.mappings[" + std::to_string(i) +
                                     "].material: expected a material index");
                return material;
            }
    }
    return prim.material;
}

Result<uint32_t> Loader::materialIndex(const std::string& where, int m) {
    if (m < 0) {
        if (defaultMaterial < 0) {
            // glTF 3.9: without a material, the defaults of every property (white, fully
            // metallic, fully rough).
            Material d;
            d.name = "default";
            d.baseColor = glm::vec3(1.0f);
            d.metalMask = 1.0f;
            d.smoothness = 0.0f;
            defaultMaterial = static_cast<int32_t>(scene.materials.size());
            scene.materials.push_back(d);
        }
        return static_cast<uint32_t>(defaultMaterial);
    }
    if (size_t(m) >= model.materials.size())
        return error(ErrorCode::InvalidInput,
                     where + ": material " + std::to_string(m) + " does not exist (" +
                         std::to_string(model.materials.size()) + " materials)");
    return static_cast<uint32_t>(m);
}

Result<Primitive> Loader::primitive(size_t meshIndex, size_t primIndex,
                                    const std::vector<double>& weights, Skinning& skin) {
    const auto& mesh = model.meshes[meshIndex];
    const auto& prim = mesh.primitives[primIndex];
    const std::string where =
        named("mesh", meshIndex, mesh.name) + " primitive " + std::to_string(primIndex);
    const char* mode = modeName(prim.mode);
    if (!mode)
        return error(ErrorCode::InvalidInput, where + ": mode " + std::to_string(prim.mode) +
                                                  " is not a glTF primitive mode");
    auto attr = [&](const char* name) {
        auto it = prim.attributes.find(name);
        return it == prim.attributes.end() ? -1 : it->second;
    };
    if (attr("POSITION") < 0)
        return error(ErrorCode::InvalidInput, where + ": no POSITION attribute");
    auto compressed = draco(where, prim);
    if (!compressed) return std::unexpected(compressed.error());
    // An attribute from the Draco buffer when it holds it, else from its accessor.
    auto floats = [&](const char* semantic, int type) -> Result<std::vector<float>> {
        if (*compressed)
            if (auto d = (*compressed)->attributes.find(semantic);
                d != (*compressed)->attributes.end()) {
                const int comps = tinygltf::GetNumComponentsInType(static_cast<uint32_t>(type));
                if ((*compressed)->components[semantic] != comps)
                    return error(ErrorCode::InvalidInput,
                                 where + ": KHR_draco_mesh_compression." + semantic + " has " +
                                     std::to_string((*compressed)->components[semantic]) +
                                     " components, expected " + std::to_string(comps));
                return d->second;
            }
        return readFloats(where, semantic, attr(semantic), type);
    };
    auto pos = floats("POSITION", TINYGLTF_TYPE_VEC3);
    if (!pos) return std::unexpected(pos.error());
    const size_t n = pos->size() / 3;
    Primitive p;
    p.vertices.resize(n);
    for (size_t i = 0; i < n; ++i)
        p.vertices[i].position = glm::vec3((*pos)[3 * i], (*pos)[3 * i + 1], (*pos)[3 * i + 2]);

    // Other attributes must have as many elements as POSITION.
    auto optional = [&](const char* semantic, int type) -> Result<std::vector<float>> {
        if (attr(semantic) < 0) return std::vector<float>{};
        auto v = floats(semantic, type);
        if (!v) return v;
        const size_t comps = size_t(tinygltf::GetNumComponentsInType(static_cast<uint32_t>(type)));
        if (v->size() / comps != n)
            return error(ErrorCode::InvalidInput,
                         where + ": " + semantic + ": accessor " + std::to_string(attr(semantic)) +
                             " has " + std::to_string(v->size() / comps) +
                             " elements, POSITION has " + std::to_string(n));
        return v;
    };
    auto normals = optional("NORMAL", TINYGLTF_TYPE_VEC3);
    if (!normals) return std::unexpected(normals.error());
    auto tangents = optional("TANGENT", TINYGLTF_TYPE_VEC4);
    if (!tangents) return std::unexpected(tangents.error());
    // The material first: it says which TEXCOORD_n fill the vertex's two uv slots (uvSlots()).
    auto chosen = variantMaterial(where, prim);
    if (!chosen) return std::unexpected(chosen.error());
    auto m = materialIndex(where, *chosen);
    if (!m) return std::unexpected(m.error());
    p.material = *m;
    const std::array<int, 2> slots =
        *m < materialSlots.size() ? materialSlots[*m] : std::array<int, 2>{0, 1};
    const std::string set0 = "TEXCOORD_" + std::to_string(slots[0]),
                      set1 = "TEXCOORD_" + std::to_string(slots[1]);
    auto uv0 = optional(set0.c_str(), TINYGLTF_TYPE_VEC2);
    if (!uv0) return std::unexpected(uv0.error());
    auto uv1 = optional(set1.c_str(), TINYGLTF_TYPE_VEC2);
    if (!uv1) return std::unexpected(uv1.error());
    for (size_t i = 0; i < n; ++i) {
        Vertex& v = p.vertices[i];
        if (!normals->empty())
            v.normal = glm::vec3((*normals)[3 * i], (*normals)[3 * i + 1], (*normals)[3 * i + 2]);
        if (!tangents->empty())
            v.tangent =
                glm::vec4((*tangents)[4 * i], (*tangents)[4 * i + 1], (*tangents)[4 * i + 2],
                          (*tangents)[4 * i + 3] < 0 ? -1.0f : 1.0f);
        if (!uv0->empty()) v.uv0 = glm::vec2((*uv0)[2 * i], (*uv0)[2 * i + 1]);
        if (!uv1->empty()) v.uv1 = glm::vec2((*uv1)[2 * i], (*uv1)[2 * i + 1]);
    }
    // COLOR_0 (glTF 3.7.2.1): RGB or RGBA, float or normalised unsigned byte/short, linear.
    if (attr("COLOR_0") >= 0) {
        auto acc = accessor(where + ": COLOR_0", attr("COLOR_0"));
        if (!acc) return std::unexpected(acc.error());
        const bool rgb = (*acc)->type == TINYGLTF_TYPE_VEC3;
        auto color = optional("COLOR_0", rgb ? TINYGLTF_TYPE_VEC3 : TINYGLTF_TYPE_VEC4);
        if (!color) return std::unexpected(color.error());
        const size_t comps = rgb ? 3 : 4;
        for (size_t i = 0; i < n; ++i)
            for (size_t k = 0; k < comps; ++k)
                p.vertices[i].color[int(k)] = static_cast<uint16_t>(
                    std::lround(std::clamp((*color)[comps * i + k], 0.0f, 1.0f) * 65535.0f));
    }
    // TEXCOORD_1 is the lightmap parameterisation game teams author (charts in [0, 1]²).
    p.lightmapUv = slots[1] == 1 && !uv1->empty();
    if (auto r = morph(where, prim, weights, p, !normals->empty(), !tangents->empty()); !r)
        return std::unexpected(r.error());
    // JOINTS_n / WEIGHTS_n: kept beside the primitive for a node that skins it (skins()).
    for (int set = 0; set < 2; ++set) {
        const std::string j = "JOINTS_" + std::to_string(set), w = "WEIGHTS_" + std::to_string(set);
        if (attr(j.c_str()) < 0 && attr(w.c_str()) < 0) break;
        if (attr(j.c_str()) < 0 || attr(w.c_str()) < 0)
            return error(
                ErrorCode::InvalidInput,
                where + ": " + (attr(j.c_str()) < 0 ? w + " without " + j : j + " without " + w));
        auto joints = optional(j.c_str(), TINYGLTF_TYPE_VEC4);
        if (!joints) return std::unexpected(joints.error());
        auto amounts = optional(w.c_str(), TINYGLTF_TYPE_VEC4);
        if (!amounts) return std::unexpected(amounts.error());
        skin.influences += 4;
        skin.joints.resize(n * skin.influences);
        skin.weights.resize(n * skin.influences);
        for (size_t i = 0; i < n; ++i)
            for (size_t k = 0; k < 4; ++k) {
                const float joint = (*joints)[4 * i + k];
                if (!(joint >= 0.0f && joint < 65536.0f))
                    return error(ErrorCode::InvalidInput, where + ": " + j + "[" +
                                                              std::to_string(i) + "] names joint " +
                                                              fmt(double(joint)));
                skin.joints[i * skin.influences + size_t(4 * set) + k] = uint32_t(joint);
                skin.weights[i * skin.influences + size_t(4 * set) + k] = (*amounts)[4 * i + k];
            }
    }

    std::vector<uint32_t> idx;
    if (*compressed) {
        idx = std::move((*compressed)->indices);
        for (uint32_t i : idx)
            if (i >= n)
                return error(ErrorCode::InvalidInput,
                             where + ": KHR_draco_mesh_compression: index " + std::to_string(i) +
                                 " beyond the " + std::to_string(n) + " vertices");
    } else if (prim.indices >= 0) {
        auto r = readIndices(where, prim.indices, n);
        if (!r) return std::unexpected(r.error());
        idx = std::move(*r);
    } else {
        idx.resize(n);
        for (size_t i = 0; i < n; ++i) idx[i] = static_cast<uint32_t>(i);
    }
    // Points stay as they are; strips and loops of lines become segment lists (glTF 3.7.2.1).
    if (prim.mode == TINYGLTF_MODE_POINTS) {
        p.indices = std::move(idx);
        return p;
    }
    if (prim.mode == TINYGLTF_MODE_LINE) {
        if (idx.size() % 2 != 0)
            warn(where + ": " + std::to_string(idx.size()) +
                 " indices is not a whole number of segments; the last is ignored");
        idx.resize(idx.size() - idx.size() % 2);
        p.indices = std::move(idx);
        return p;
    }
    if (prim.mode == TINYGLTF_MODE_LINE_STRIP || prim.mode == TINYGLTF_MODE_LINE_LOOP) {
        for (size_t i = 0; i + 1 < idx.size(); ++i)
            p.indices.insert(p.indices.end(), {idx[i], idx[i + 1]});
        if (prim.mode == TINYGLTF_MODE_LINE_LOOP && idx.size() > 2)
            p.indices.insert(p.indices.end(), {idx.back(), idx.front()});
        return p;
    }
    // Strips and fans become lists; a strip's odd triangles swap two corners to stay CCW.
    if (prim.mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
        for (size_t i = 0; i + 2 < idx.size(); ++i)
            if (i % 2 == 0)
                p.indices.insert(p.indices.end(), {idx[i], idx[i + 1], idx[i + 2]});
            else
                p.indices.insert(p.indices.end(), {idx[i + 1], idx[i], idx[i + 2]});
    } else if (prim.mode == TINYGLTF_MODE_TRIANGLE_FAN) {
        for (size_t i = 1; i + 1 < idx.size(); ++i)
            p.indices.insert(p.indices.end(), {idx[0], idx[i], idx[i + 1]});
    } else {
        if (idx.size() % 3 != 0)
            warn(where + ": " + std::to_string(idx.size()) +
                 " indices is not a whole number of triangles; the last " +
                 std::to_string(idx.size() % 3) + " are ignored");
        idx.resize(idx.size() - idx.size() % 3);
        p.indices = std::move(idx);
    }

    // glTF 3.7.2.1: without normals, flat normals, and tangents are then ignored. Flat normals
    // give each triangle its own corners: the skinning data follows them, and a skinned copy
    // makes both anew from its posed positions.
    skin.flatNormals = normals->empty();
    skin.generatedTangents = normals->empty() || tangents->empty();
    if (normals->empty() && skin.influences > 0) {
        Skinning corners{skin.influences, {}, {}, true, true};
        for (uint32_t i : p.indices)
            for (size_t k = 0; k < skin.influences; ++k) {
                corners.joints.push_back(skin.joints[i * skin.influences + k]);
                corners.weights.push_back(skin.weights[i * skin.influences + k]);
            }
        skin = std::move(corners);
    }
    if (normals->empty())
        generateFlatNormals(p);
    else
        for (auto& v : p.vertices) {
            // Renormalise only what is not unit already, so written normals load back bit-exact.
            const float len = glm::length(v.normal);
            if (!(len > 0.0f))
                v.normal = glm::vec3(0, 0, 1);
            else if (std::fabs(len - 1.0f) > 1e-6f)
                v.normal /= len;
        }
    // From the uv set the material's normal map reads (its slot, uvSlots()); a vertex split
    // between mirrored uv halves takes its skinning data along.
    if (normals->empty() || tangents->empty()) {
        const uint32_t slot =
            *m < scene.materials.size() ? std::min(scene.materials[*m].normalTex.texCoord, 1u) : 0u;
        for (uint32_t from : generateTangents(p, slot))
            for (size_t k = 0; k < skin.influences; ++k) {
                skin.joints.push_back(skin.joints[size_t(from) * skin.influences + k]);
                skin.weights.push_back(skin.weights[size_t(from) * skin.influences + k]);
            }
    }
    return p;
}

// glTF mesh m at the given morph weights; its primitives' skinning data is pushed onto
// meshSkinning beside the Scene mesh it becomes (triangles, then lines, then points: the order
// skins() poses them in).
Result<Mesh> Loader::mesh(size_t m, const std::vector<double>& weights) {
    Mesh mesh;
    mesh.name = model.meshes[m].name.empty() ? "mesh " + std::to_string(m) : model.meshes[m].name;
    std::vector<Skinning> skinning[3];
    for (size_t p = 0; p < model.meshes[m].primitives.size(); ++p) {
        const int mode = model.meshes[m].primitives[p].mode;
        const int kind = mode == TINYGLTF_MODE_POINTS ? 2
                         : mode == TINYGLTF_MODE_LINE || mode == TINYGLTF_MODE_LINE_LOOP ||
                                 mode == TINYGLTF_MODE_LINE_STRIP
                             ? 1
                             : 0;
        Skinning skin;
        auto prim = primitive(m, p, weights, skin);
        if (!prim) return std::unexpected(prim.error());
        (kind == 0   ? mesh.primitives
         : kind == 1 ? mesh.lines
                     : mesh.points)
            .push_back(std::move(*prim));
        skinning[kind].push_back(std::move(skin));
    }
    for (int kind = 1; kind < 3; ++kind)
        skinning[0].insert(skinning[0].end(), skinning[kind].begin(), skinning[kind].end());
    meshSkinning.push_back(std::move(skinning[0]));
    return mesh;
}

Result<void> Loader::meshes() {
    for (size_t m = 0; m < model.meshes.size(); ++m) {
        const std::string where = named("mesh", m, model.meshes[m].name) + ": weights";
        if (auto r = morphWeights(m, model.meshes[m].weights, where); !r)
            return std::unexpected(r.error());
        auto mesh = this->mesh(m, model.meshes[m].weights);
        if (!mesh) return std::unexpected(mesh.error());
        scene.meshes.push_back(std::move(*mesh));
    }
    return {};
}

}  // namespace gltf_load

}  // namespace rg

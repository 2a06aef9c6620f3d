// Inside loadGltf(): the Loader that reads a glTF file into a Scene, one file per part of glTF
// (gltf_load_accessors/meshes/materials/nodes.cpp), and the file read and checked before
// tinygltf runs, the messages and the steps in order (gltf_load.cpp). Internal to rg_scene.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "scene.h"
#include "tinygltf.h"

namespace rg::gltf_load {

// keepEncodedImage's state (gltf_load.cpp): the model tinygltf fills, and what is wrong with
// which image.
struct ImageCallbackState {
    const tinygltf::Model* model = nullptr;
    std::map<int, std::string> errors;  // image index -> what is wrong
};

struct Preflight;  // gltf_load.cpp

// A "data:" URI (the bytes are in the URI, not in a file).
bool isDataUri(const std::string& uri);

struct Loader {
    std::string path;  // as given: every message starts with it
    GltfOptions options;
    std::filesystem::path dir;  // the file's folder, as given (for messages) and for resolving uris
    tinygltf::Model model;
    ImageCallbackState imageState;
    Scene scene;
    std::map<std::pair<int, bool>, int32_t> images;  // (glTF image, srgb) -> Scene image
    std::vector<int32_t> samplers;                   // glTF sampler -> Scene sampler
    int32_t defaultMaterial = -1;
    std::set<int> basisuWarned;  // textures whose KHR_texture_basisu fallback was named

    // ---- messages and file names (gltf_load.cpp) --------------------------------------------

    std::unexpected<Error> error(ErrorCode code, const std::string& msg) const;
    void warn(const std::string& msg);  // a line of Scene::warnings
    static std::string named(const std::string& what, size_t index, const std::string& name);
    std::string resolve(const std::string& uri) const;
    Result<std::string> extrasFile(const std::string& name, const std::string& label) const;
    Result<std::string> resolveInside(const std::string& uri, const std::string& label) const;
    void addFile(const std::string& p);

    // ---- reading the file (gltf_load.cpp) ---------------------------------------------------

    Result<Preflight> preflight(const std::vector<unsigned char>& bytes);
    Result<void> checkExtensions(const nlohmann::json& j);
    Result<void> checkSchema(const nlohmann::json& j);  // gltf_load_schema.cpp
    Result<void> checkBuffers(const nlohmann::json& j);
    static bool dropDracoIndices(nlohmann::json& j);  // true when it changed the JSON
    // EXT_meshopt_compression (gltf_load_meshopt.cpp): fallback buffers (no bytes in the file)
    // by index with their declared byteLength; the JSON tinygltf reads gives each a placeholder
    // byte, and meshopt() decodes the compressed views into them.
    std::map<size_t, uint64_t> meshoptFallbacks;
    bool placeholdMeshoptFallbacks(nlohmann::json& j);  // true when it changed the JSON
    Result<void> meshopt();
    Result<void> parse();

    // ---- accessors (gltf_load_accessors.cpp) ------------------------------------------------

    struct View {
        const unsigned char* data = nullptr;  // first element
        size_t stride = 0;
    };

    Result<View> viewRange(const std::string& what, int viewIndex, size_t offset, size_t count,
                           size_t elementSize, bool allowStride);
    Result<const tinygltf::Accessor*> accessor(const std::string& what, int index);
    Result<std::vector<float>> readFloats(const std::string& where, const std::string& semantic,
                                          int index, int type);
    Result<std::vector<uint32_t>> readIndices(const std::string& where, int index,
                                              size_t vertexCount);

    // ---- meshes (gltf_load_meshes.cpp) ------------------------------------------------------

    Result<uint32_t> materialIndex(const std::string& where, int m);
    int variant = -1;  // KHR_materials_variants: options.variant's index, -1 for the defaults
    Result<void> chooseVariant();
    // The glTF material a primitive takes in the chosen variant (its own without one).
    Result<int> variantMaterial(const std::string& where, const tinygltf::Primitive& prim);
    // Skinning data a primitive carries for a node that skins it: `influences` joints per
    // vertex (4 per JOINTS_n / WEIGHTS_n pair), vertex-major.
    struct Skinning {
        size_t influences = 0;
        std::vector<uint32_t> joints;
        std::vector<float> weights;
        bool flatNormals = false;        // generated: made anew once posed
        bool generatedTangents = false;  // the same
    };
    std::vector<std::vector<Skinning>> meshSkinning;  // per Scene mesh, per primitive
    Result<Primitive> primitive(size_t meshIndex, size_t primIndex,
                                const std::vector<double>& weights, Skinning& skin);
    Result<Mesh> mesh(size_t m, const std::vector<double>& weights);
    // KHR_draco_mesh_compression's decoded attributes (by glTF semantic) and triangle list
    // (gltf_load_draco.cpp); none for a primitive without it.
    struct Draco {
        std::map<std::string, std::vector<float>> attributes;
        std::map<std::string, int> components;
        std::vector<uint32_t> indices;
        uint32_t points = 0;
    };
    Result<std::optional<Draco>> draco(const std::string& where, const tinygltf::Primitive& prim);
    Result<void> meshes();

    // ---- morph targets and skins (gltf_load_skin.cpp) ---------------------------------------

    // Mesh m's weights (its own or a node's) checked against its primitives' morph targets.
    Result<void> morphWeights(size_t m, const std::vector<double>& weights,
                              const std::string& where);
    Result<void> morph(const std::string& where, const tinygltf::Primitive& prim,
                       const std::vector<double>& weights, Primitive& p, bool normals,
                       bool tangents);
    std::map<std::pair<int, std::vector<double>>, int32_t>
        morphed;                                 // (mesh, weights) -> Scene mesh
    Result<int32_t> nodeMesh(size_t nodeIndex);  // the node's mesh at the node's weights
    // Vertices in the copies morphed or posed per node, and their bound (a hostile file with many
    // skinned nodes must not exhaust memory).
    size_t copiedVertices = 0;
    static constexpr size_t kMaxCopiedVertices = size_t(1) << 24;
    Result<void> copying(const Mesh& mesh, const std::string& where);
    struct SkinnedNode {
        size_t node;       // glTF node
        size_t sceneNode;  // its Scene node, posed by skins()
    };
    std::vector<SkinnedNode> skinned;
    // Per Scene node the walk made: its glTF node, and what lies below that node's transform (an
    // EXT_mesh_gpu_instancing instance's; identity otherwise) — what an animation moves.
    std::vector<std::pair<size_t, glm::mat4>> nodeSources;
    // Per glTF node, the node the walk entered it from: −1 a root of the scene, −2 not entered.
    std::vector<int32_t> walkParent;
    // The animation options.animation chooses (gltf_load_animation.cpp): read, checked and given
    // to the Scene nodes under the nodes it moves, each placed where it has them at time 0.
    Result<void> animations();
    Result<Animation::Sampler> animationSampler(const std::string& where,
                                                const tinygltf::AnimationSampler& s,
                                                const std::string& path);
    std::vector<std::optional<glm::mat4>> worlds;  // per glTF node, once the walk has entered it
    std::vector<int> parents;                      // per glTF node (-1: a root), built on demand
    Result<glm::mat4> worldOf(size_t node);
    Result<void> skins();

    // ---- numbers glTF gives a range, JSON values (gltf_load.cpp) ----------------------------

    static std::string fmt(double v);
    Result<float> ranged(const std::string& what, double v, double lo, double hi) const;
    Result<glm::vec3> ranged3(const std::string& what, const std::vector<double>& v, glm::vec3 def,
                              double lo, double hi) const;
    static double number(const tinygltf::Value& v, double def);
    static int indexOf(const tinygltf::Value& v);
    static glm::vec3 vec3Of(const std::vector<double>& v, glm::vec3 def);
    static glm::vec3 vec3Of(const tinygltf::Value& v, glm::vec3 def);

    // ---- materials, textures, images (gltf_load_materials.cpp) ------------------------------

    void convertSamplers();
    Result<int32_t> image(const std::string& where, int index, bool srgb);
    static glm::mat3 uvTransform(glm::vec2 offset, float rotation, glm::vec2 scale);
    Result<TextureRef> texture(const std::string& where, int index, int texCoord,
                               const tinygltf::ExtensionMap& ext, bool srgb);
    static Value toValue(const tinygltf::Value& v);
    Result<void> materials();
    static constexpr int kMaxTexCoord = 31;  // TEXCOORD_n a texture may name
    // Per Scene material: the glTF TEXCOORD_n each of a vertex's two uv slots holds.
    std::vector<std::array<int, 2>> materialSlots;
    void uvSlots(const std::string& where, Material& m);
    Result<TextureRef> extensionTexture(const std::string& where, const tinygltf::Value& info,
                                        bool srgb);
    Result<float> reflectanceOf(const tinygltf::Material& src, const std::string& where);
    Result<void> specularGlossiness(const tinygltf::Material& src, const std::string& where,
                                    Material& m);
    Result<void> clearCoat(const tinygltf::Material& src, const std::string& where, Material& m);
    Result<void> sheen(const tinygltf::Material& src, const std::string& where, Material& m);
    bool takesModel(const std::string& where, const char* extension, const char* keeps,
                    Material& m);
    Result<void> transmission(const tinygltf::Material& src, const std::string& where, Material& m);
    std::vector<size_t> volumes;  // Scene materials with a volume in their mesh's space
    void volumeScale();           // ...times the scale of the nodes drawing them

    // ---- nodes, cameras, lights (gltf_load_nodes.cpp) ---------------------------------------

    Result<glm::mat4> localTransform(size_t index);
    static constexpr size_t kMaxInstances = size_t(1) << 20;  // EXT_mesh_gpu_instancing, per node
    Result<void> instances(size_t index, const std::string& name, const glm::mat4& world,
                           int32_t mesh);
    Result<void> camera(size_t nodeIndex, const glm::mat4& world);
    Result<void> light(size_t nodeIndex, const glm::mat4& world);
    Result<void> enter(size_t index, const glm::mat4& parent, std::vector<bool>& onPath,
                       std::vector<bool>& seen, size_t depth, glm::mat4& world);
    Result<void> visit(size_t root, const glm::mat4& parent, std::vector<bool>& onPath,
                       std::vector<bool>& seen, size_t depth);
    Result<void> environment(const tinygltf::Value& extras);
    Result<void> nodes();

    // ---- all of it (gltf_load.cpp) ----------------------------------------------------------

    Result<Scene> run();
};

}  // namespace rg::gltf_load

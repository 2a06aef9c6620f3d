// Inside loadGltf(): the Loader that reads a glTF file into a Scene, one file per part of glTF
// (gltf_load_accessors/meshes/materials/nodes.cpp), and the file read and checked before
// tinygltf runs, the messages and the steps in order (gltf_load.cpp). Internal to rg_scene.
#pragma once

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
    Result<Primitive> primitive(size_t meshIndex, size_t primIndex);
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
    Result<float> reflectanceOf(const tinygltf::Material& src, const std::string& where);
    Result<void> specularGlossiness(const tinygltf::Material& src, const std::string& where,
                                    Material& m);
    Result<void> clearCoat(const tinygltf::Material& src, const std::string& where, Material& m);

    // ---- nodes, cameras, lights (gltf_load_nodes.cpp) ---------------------------------------

    Result<glm::mat4> localTransform(size_t index);
    static constexpr size_t kMaxInstances = size_t(1) << 20;  // EXT_mesh_gpu_instancing, per node
    Result<void> instances(size_t index, const std::string& name, const glm::mat4& world);
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

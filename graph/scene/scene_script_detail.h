// Inside loadSceneScript(): the Builder that checks a script's declarations and builds the Scene,
// one file per kind of piece (scene_script_objects/lights/camera.cpp), the field checks they share
// (scene_script_fields.cpp) and the steps in order (scene_script.cpp). Internal to rg_scene.
#pragma once

#include <cmath>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "lua/declarations.h"
#include "scene.h"

namespace rg::scene_script {

constexpr float kDegrees = 3.14159265358979f / 180.0f;

// Field checks (scene_script_fields.cpp), and how their messages show a number and a value.
std::string formatNumber(double d);
std::string describe(const Value& v, int depth = 0);

// A numeric constraint and how an error words it ("a number > 0").
struct Range {
    double lo = -HUGE_VAL, hi = HUGE_VAL;
    bool loOpen = false, hiOpen = false;
    bool integer = false;

    static Range any() { return {}; }
    static Range positive() { return {0, HUGE_VAL, true, false}; }
    static Range nonNegative() { return {0, HUGE_VAL, false, false}; }
    static Range unit() { return {0, 1, false, false}; }
    static Range closed(double a, double b) { return {a, b, false, false}; }
    static Range openLow(double a, double b) { return {a, b, true, false}; }
    static Range open(double a, double b) { return {a, b, true, true}; }

    bool contains(double v) const {
        if (!std::isfinite(v)) return false;
        if (integer && std::floor(v) != v) return false;
        return (loOpen ? v > lo : v >= lo) && (hiOpen ? v < hi : v <= hi);
    }
    std::string words(const char* noun = "a number") const {
        std::string n = integer ? "a whole number" : noun;
        const bool hasLo = lo != -HUGE_VAL, hasHi = hi != HUGE_VAL;
        if (hasLo && hasHi)
            return n + " in " + (loOpen ? "(" : "[") + formatNumber(lo) + ", " + formatNumber(hi) +
                   (hiOpen ? ")" : "]");
        if (hasLo) return n + (loOpen ? " > " : " >= ") + formatNumber(lo);
        if (hasHi) return n + (hiOpen ? " < " : " <= ") + formatNumber(hi);
        return n;
    }
};

Result<double> number(const Where& w, const Value& body, const std::string& field, double def,
                      Range range);
Result<float> numberF(const Where& w, const Value& body, const std::string& field, float def,
                      Range range);
Result<std::vector<float>> numbers(const Where& w, const Value& v, size_t n,
                                   const std::string& shape, Range range);
Result<glm::vec3> vec3(const Where& w, const Value& body, const std::string& field, glm::vec3 def,
                       const std::string& shape = "{x, y, z}", Range range = Range::any());
Result<glm::vec3> colour(const Where& w, const Value& body, const std::string& field, glm::vec3 def,
                         Range range = Range::unit());
Result<std::string> string(const Where& w, const Value& body, const std::string& field,
                           const std::string& def);
Result<std::string> choice(const Where& w, const Value& body, const std::string& field,
                           const std::string& def, const std::vector<std::string>& allowed,
                           const std::string& what);
Result<bool> boolean(const Where& w, const Value& body, const std::string& field, bool def);

struct Builder {
    const std::string& scriptPath;
    const SceneScriptOptions& options;
    Scene scene;
    std::map<std::string, uint32_t> materials;  // name -> index
    std::vector<std::string> materialNames;
    std::map<std::string, const Declaration*> seen[static_cast<size_t>(DeclKind::Count)];
    const Declaration* firstEnvironment = nullptr;
    const Declaration* firstLightmap = nullptr;
    size_t generatedVertices =
        0;  // budget for sphere/plane/box meshes (a script is a loop away from millions)
    static constexpr size_t kMaxGeneratedVertices = size_t(1) << 24;
    // Generated meshes by what made them (kind, dimensions, segments, material): nodes declared
    // alike share one mesh — uploaded, simplified and counted against the budget once.
    std::map<std::string, int32_t> generatedMeshes;

    // ---- files and transforms (scene_script.cpp) ---------------------------------------------

    static Where where(const Declaration& d);
    std::string resolve(const std::string& file) const;
    void addFile(const std::string& p);
    Result<std::string> existingFile(const Where& w, const Value& body, const std::string& field);
    Result<int32_t> textureFile(const Where& w, const Value& b, const std::string& field,
                                bool srgb);
    static Result<glm::mat4> transform(const Where& w, const Value& b);
    // An object's or glTF file's `path` (a move: keys { time, position, rotation }, each field
    // defaulting to the declaration's own) on nodes [first, scene.nodes.size()), which the
    // declaration placed with `transform`: each node becomes dynamic and keeps the part of its
    // transform below the placement (scale, a glTF node's own). Nothing without a `path`.
    Result<void> nodePath(const Where& w, const Value& b, size_t first);

    // ---- declarations ----------------------------------------------------------------------

    Result<void> names(const std::vector<Declaration>& decls);  // scene_script.cpp

    // Materials, objects, glTF files, decals (scene_script_objects.cpp).
    Result<void> material(const Declaration& d);
    Result<uint32_t> materialRef(const Where& w, const Value& b);
    Result<void> object(const Declaration& d);
    void merge(Scene&& sub, const glm::mat4& t, const std::string& prefix);
    Result<void> gltf(const Declaration& d);
    Result<void> decal(const Declaration& d);

    // Lights, the environment, the lightmap, probes (scene_script_lights.cpp).
    Result<void> light(const Declaration& d);
    Result<void> environment(const Declaration& d);
    Result<void> lightmap(const Declaration& d);
    Result<void> probe(const Declaration& d);

    // Cameras (scene_script_camera.cpp).
    Result<void> camera(const Declaration& d);
    void defaultCamera();

    // ---- all of it (scene_script.cpp) --------------------------------------------------------

    Result<Scene> build(const std::vector<Declaration>& decls);
};

}  // namespace rg::scene_script

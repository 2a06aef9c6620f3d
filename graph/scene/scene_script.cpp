// Lua scene scripts -> Scene. The host runs the script and hands back scene.* declarations as
// plain Values; this file checks each against its schema (the same wording as the pipeline's
// declarations.cpp: "file:line: scene.sphere.ball.radius: expected a number > 0, got -1") and
// builds the meshes, materials, lights, cameras and environment.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <map>

#include <glm/gtc/matrix_transform.hpp>

#include "core/light_units.h"
#include "lua/declarations.h"
#include "lua/lua_host.h"
#include "scene.h"
#include "scene_detail.h"

namespace fs = std::filesystem;

namespace rg {

using namespace scene_detail;

namespace {

constexpr float kDegrees = 3.14159265358979f / 180.0f;

std::string formatNumber(double d) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", d);
    return buf;
}

// A value as an error message shows it: -1, "text", {1, 2, 3}, a table, a boolean.
std::string describe(const Value& v, int depth = 0) {
    if (v.isNumber()) return formatNumber(v.asNumber());
    if (v.isString()) return "\"" + v.asString() + "\"";
    if (v.isBool()) return v.asBool() ? "true" : "false";
    if (v.isList()) {
        if (depth > 0) return "a list";
        std::string s = "{";
        for (size_t i = 0; i < v.asList().size() && i < 6; ++i) s += (i ? ", " : "") + describe(v.asList()[i], depth + 1);
        return s + (v.asList().size() > 6 ? ", ...}" : "}");
    }
    if (v.isTable()) return "a table";
    return "nil";
}

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
            return n + " in " + (loOpen ? "(" : "[") + formatNumber(lo) + ", " + formatNumber(hi) + (hiOpen ? ")" : "]");
        if (hasLo) return n + (loOpen ? " > " : " >= ") + formatNumber(lo);
        if (hasHi) return n + (hiOpen ? " < " : " <= ") + formatNumber(hi);
        return n;
    }
};

Result<double> number(const Where& w, const Value& body, const std::string& field, double def, Range range) {
    const Value& v = body[field];
    if (v.isNil()) return def;
    if (!v.isNumber() || !range.contains(v.asNumber())) return w.at(field).error("expected " + range.words() + ", got " + describe(v));
    return v.asNumber();
}

Result<float> numberF(const Where& w, const Value& body, const std::string& field, float def, Range range) {
    auto r = number(w, body, field, def, range);
    if (!r) return std::unexpected(r.error());
    return static_cast<float>(*r);
}

// A list of `n` numbers, each within `range`; `shape` names them in messages ("{x, y, z}").
Result<std::vector<float>> numbers(const Where& w, const Value& v, size_t n, const std::string& shape, Range range) {
    bool ok = v.isList() && v.asList().size() == n;
    if (ok)
        for (const auto& e : v.asList()) ok = ok && e.isNumber() && range.contains(e.asNumber());
    if (!ok) {
        const std::string each = range.lo == -HUGE_VAL && range.hi == HUGE_VAL ? " (" + std::to_string(n) + " numbers)"
                                                                               : " with each value " + range.words("").substr(1);
        return w.error("expected " + shape + each + ", got " + describe(v));
    }
    std::vector<float> out;
    for (const auto& e : v.asList()) out.push_back(static_cast<float>(e.asNumber()));
    return out;
}

Result<glm::vec3> vec3(const Where& w, const Value& body, const std::string& field, glm::vec3 def,
                       const std::string& shape = "{x, y, z}", Range range = Range::any()) {
    const Value& v = body[field];
    if (v.isNil()) return def;
    auto r = numbers(w.at(field), v, 3, shape, range);
    if (!r) return std::unexpected(r.error());
    return glm::vec3((*r)[0], (*r)[1], (*r)[2]);
}

Result<glm::vec3> colour(const Where& w, const Value& body, const std::string& field, glm::vec3 def, Range range = Range::unit()) {
    return vec3(w, body, field, def, "{r, g, b}", range);
}

Result<std::string> string(const Where& w, const Value& body, const std::string& field, const std::string& def) {
    const Value& v = body[field];
    if (v.isNil()) return def;
    if (!v.isString() || v.asString().empty()) return w.at(field).error("expected a string, got " + describe(v));
    return v.asString();
}

Result<std::string> choice(const Where& w, const Value& body, const std::string& field, const std::string& def,
                           const std::vector<std::string>& allowed, const std::string& what) {
    auto s = string(w, body, field, def);
    if (!s) return s;
    if (std::find(allowed.begin(), allowed.end(), *s) == allowed.end())
        return w.at(field).error("unknown " + what + " '" + *s + "'" + suggestion(*s, allowed) + "; expected one of: " + joinQuoted(allowed));
    return s;
}

Result<bool> boolean(const Where& w, const Value& body, const std::string& field, bool def) {
    const Value& v = body[field];
    if (v.isNil()) return def;
    if (!v.isBool()) return w.at(field).error("expected a boolean, got " + describe(v));
    return v.asBool();
}

struct Builder {
    const std::string& scriptPath;
    const SceneScriptOptions& options;
    Scene scene;
    std::map<std::string, uint32_t> materials;  // name -> index
    std::vector<std::string> materialNames;
    std::map<std::string, const Declaration*> seen[static_cast<size_t>(DeclKind::Count)];
    const Declaration* firstEnvironment = nullptr;
    const Declaration* firstLightmap = nullptr;
    size_t generatedVertices = 0;  // budget for sphere/plane/box meshes (a script is a loop away from millions)
    static constexpr size_t kMaxGeneratedVertices = size_t(1) << 24;

    static Where where(const Declaration& d) { return {d, std::string(declKindName(d.kind)) + "." + d.name}; }

    // Files named in a script are relative to the script's folder.
    std::string resolve(const std::string& file) const {
        fs::path p(file);
        if (p.is_absolute()) return p.string();
        return (fs::path(scriptPath).parent_path() / p).lexically_normal().string();
    }
    void addFile(const std::string& p) {
        std::error_code ec;
        std::string a = fs::weakly_canonical(fs::absolute(p), ec).string();
        if (ec) a = p;
        if (std::find(scene.files.begin(), scene.files.end(), a) == scene.files.end()) scene.files.push_back(a);
    }
    Result<std::string> existingFile(const Where& w, const Value& body, const std::string& field) {
        const Value& v = body[field];
        if (!v.isString() || v.asString().empty()) return w.at(field).error("expected a file name, got " + describe(v));
        const std::string path = resolve(v.asString());
        std::error_code ec;
        if (!fs::is_regular_file(path, ec)) {
            auto r = readFile(path);  // for the OS's reason
            return w.at(field).error(r ? "'" + path + "' is not a regular file" : r.error().message);
        }
        addFile(path);
        return path;
    }

    // A texture file of a material: decoded once per file and encoding, its index in scene.images.
    Result<int32_t> textureFile(const Where& w, const Value& b, const std::string& field, bool srgb) {
        std::string path;
        RG_TRY(path, existingFile(w, b, field));
        for (size_t i = 0; i < scene.images.size(); ++i)
            if (scene.images[i].name == path && scene.images[i].srgb == srgb) return static_cast<int32_t>(i);
        auto bytes = readFile(path);
        if (!bytes) return w.at(field).error(bytes.error().message);
        auto image = decodeImage(bytes->data(), bytes->size());
        if (!image) return w.at(field).error("cannot decode " + quote(path) + ": " + image.error().message);
        SceneImage si;
        si.name = path;
        si.pixels = std::move(*image);
        si.srgb = srgb;
        scene.images.push_back(std::move(si));
        return static_cast<int32_t>(scene.images.size() - 1);
    }

    static Result<glm::mat4> transform(const Where& w, const Value& b) {
        glm::vec3 position, rotation, scale(1.0f);
        RG_TRY(position, vec3(w, b, "position", glm::vec3(0.0f)));
        RG_TRY(rotation, vec3(w, b, "rotation", glm::vec3(0.0f), "{x, y, z} in degrees"));
        const Value& s = b["scale"];
        if (s.isNumber()) {
            if (!Range::positive().contains(s.asNumber()))
                return w.at("scale").error("expected a number > 0 or {x, y, z} of numbers > 0, got " + describe(s));
            scale = glm::vec3(static_cast<float>(s.asNumber()));
        } else if (!s.isNil()) {
            if (!s.isList()) return w.at("scale").error("expected a number > 0 or {x, y, z} of numbers > 0, got " + describe(s));
            RG_TRY(scale, vec3(w, b, "scale", scale, "{x, y, z}", Range::positive()));
        }
        // Rotation in degrees about X, then Y, then Z (R = Rz * Ry * Rx).
        glm::mat4 m = glm::translate(glm::mat4(1.0f), position);
        m = glm::rotate(m, rotation.z * kDegrees, glm::vec3(0, 0, 1));
        m = glm::rotate(m, rotation.y * kDegrees, glm::vec3(0, 1, 0));
        m = glm::rotate(m, rotation.x * kDegrees, glm::vec3(1, 0, 0));
        return glm::scale(m, scale);
    }

    // ---- declarations -----------------------------------------------------------------------

    Result<void> names(const std::vector<Declaration>& decls) {
        for (const auto& d : decls) {
            Where w = where(d);
            if (!isSceneKind(d.kind))
                return fail(ErrorCode::InvalidInput, d.origin + ": rg." + declKindName(d.kind) + " \"" + d.name +
                                                         "\" belongs in a pipeline script, not in a scene");
            if (!d.body.isTable()) return w.error("expected a table of fields after " + std::string(declKindName(d.kind)) + " \"" + d.name + "\", got " + describe(d.body));
            // Objects (meshes) share one namespace: each becomes a node of that name.
            DeclKind slot = d.kind == DeclKind::Plane || d.kind == DeclKind::Box || d.kind == DeclKind::Gltf ? DeclKind::Sphere : d.kind;
            auto [it, fresh] = seen[static_cast<size_t>(slot)].emplace(d.name, &d);
            if (!fresh)
                return w.error(std::string(declKindName(it->second->kind)) + " '" + d.name + "' is already declared (at " + it->second->origin + ")");
            if (d.kind == DeclKind::Lightmap) {
                if (firstLightmap) return w.error("a scene has one lightmap; '" + firstLightmap->name + "' is declared at " + firstLightmap->origin);
                firstLightmap = &d;
            }
            if (d.kind == DeclKind::Environment) {
                if (firstEnvironment)
                    return w.error("a scene has one environment; '" + firstEnvironment->name + "' is declared at " + firstEnvironment->origin);
                firstEnvironment = &d;
            }
        }
        return {};
    }

    Result<void> material(const Declaration& d) {
        Where w = where(d);
        const Value& b = d.body;
        if (auto r = checkFields(w, b, {"model", "base_color", "smoothness", "metal_mask", "reflectance", "ao", "emissive", "opacity",
                                        "diffuse_color", "f0", "params", "double_sided", "alpha", "alpha_cutoff", "base_color_map",
                                        "metallic_roughness_map", "normal_map", "normal_scale", "occlusion_map", "emissive_map", "doc"});
            !r)
            return r;
        Material m;
        m.name = d.name;
        RG_TRY(m.model, string(w, b, "model", "standard"));
        const bool twoColour = m.model == "two_colour";
        if (twoColour) {
            for (const char* f : {"base_color", "metal_mask", "reflectance"})
                if (b.has(f)) return w.at(f).error("not used by model 'two_colour', which takes diffuse_color and f0");
        } else {
            for (const char* f : {"diffuse_color", "f0"})
                if (b.has(f)) return w.at(f).error("applies to model 'two_colour' only (this material's model is '" + m.model + "')");
        }
        RG_TRY(m.baseColor, colour(w, b, "base_color", m.baseColor));
        RG_TRY(m.smoothness, numberF(w, b, "smoothness", m.smoothness, Range::unit()));
        RG_TRY(m.metalMask, numberF(w, b, "metal_mask", m.metalMask, Range::unit()));
        RG_TRY(m.reflectance, numberF(w, b, "reflectance", m.reflectance, Range::unit()));
        RG_TRY(m.ao, numberF(w, b, "ao", m.ao, Range::unit()));
        RG_TRY(m.opacity, numberF(w, b, "opacity", m.opacity, Range::unit()));
        RG_TRY(m.emissive, colour(w, b, "emissive", m.emissive, Range::nonNegative()));
        RG_TRY(m.diffuseColor, colour(w, b, "diffuse_color", m.diffuseColor));
        RG_TRY(m.f0, colour(w, b, "f0", m.f0));
        if (b.has("params") && !b["params"].isTable() && !(b["params"].isList() && b["params"].asList().empty()))
            return w.at("params").error("expected a table of named parameters, got " + describe(b["params"]));
        m.extra = b["params"];
        m.origin = d.origin + ": " + w.path;
        RG_TRY(m.doubleSided, boolean(w, b, "double_sided", false));
        std::string alpha;
        RG_TRY(alpha, choice(w, b, "alpha", "opaque", {"opaque", "mask", "blend"}, "alpha mode"));
        m.alphaMode = alpha == "mask" ? AlphaMode::Mask : alpha == "blend" ? AlphaMode::Blend : AlphaMode::Opaque;
        if (b.has("alpha_cutoff") && m.alphaMode != AlphaMode::Mask) return w.at("alpha_cutoff").error("applies to alpha = \"mask\" only");
        RG_TRY(m.alphaCutoff, numberF(w, b, "alpha_cutoff", m.alphaCutoff, Range::unit()));
        // Texture files (PNG or JPEG, relative to the script), as glTF's five maps: base colour and
        // emissive are sRGB, the others linear; each multiplies its factor.
        const std::pair<const char*, std::pair<TextureRef*, bool>> maps[] = {
            {"base_color_map", {&m.baseColorTex, true}},          {"metallic_roughness_map", {&m.metallicRoughnessTex, false}},
            {"normal_map", {&m.normalTex, false}},                {"occlusion_map", {&m.occlusionTex, false}},
            {"emissive_map", {&m.emissiveTex, true}}};
        for (const auto& [field, target] : maps)
            if (b.has(field)) RG_TRY(target.first->image, textureFile(w, b, field, target.second));
        if (b.has("normal_scale") && !b.has("normal_map")) return w.at("normal_scale").error("applies with a normal_map only");
        RG_TRY(m.normalScale, numberF(w, b, "normal_scale", m.normalScale, Range::closed(0, 10)));
        materials[d.name] = static_cast<uint32_t>(scene.materials.size());
        materialNames.push_back(d.name);
        scene.materials.push_back(std::move(m));
        return {};
    }

    Result<uint32_t> materialRef(const Where& w, const Value& b) {
        const Value& v = b["material"];
        if (v.isNil()) {
            // The material named "default" when the script declares one, else a grey dielectric.
            if (auto it = materials.find("default"); it != materials.end()) return it->second;
            Material m;
            m.name = "default";
            materials["default"] = static_cast<uint32_t>(scene.materials.size());
            scene.materials.push_back(m);
            return materials["default"];
        }
        if (!v.isString()) return w.at("material").error("expected a material name, got " + describe(v));
        auto it = materials.find(v.asString());
        if (it == materials.end())
            return w.at("material").error("unknown material '" + v.asString() + "'" + suggestion(v.asString(), materialNames) +
                                          (materialNames.empty() ? "; the scene declares no scene.material"
                                                                 : "; declared: " + joinQuoted(materialNames)));
        return it->second;
    }

    Result<void> object(const Declaration& d) {
        Where w = where(d);
        const Value& b = d.body;
        std::vector<std::string> fields = {"position", "rotation", "scale", "material", "cast_shadows", "doc"};
        if (d.kind == DeclKind::Sphere) fields.insert(fields.end(), {"radius", "segments"});
        else fields.push_back("size");
        if (auto r = checkFields(w, b, fields); !r) return r;
        glm::mat4 world;
        RG_TRY(world, transform(w, b));
        uint32_t material = 0;
        RG_TRY(material, materialRef(w, b));
        Primitive p;
        if (d.kind == DeclKind::Sphere) {
            float radius = 0.5f;
            double segments = 48;
            RG_TRY(radius, numberF(w, b, "radius", radius, Range::positive()));
            Range seg = Range::closed(3, 1024);
            seg.integer = true;
            RG_TRY(segments, number(w, b, "segments", segments, seg));
            const auto s = static_cast<size_t>(segments);
            if (generatedVertices + (s + 1) * (std::max<size_t>(s / 2, 2) + 1) > kMaxGeneratedVertices)
                return w.error("the scene's generated meshes would have more than " + std::to_string(kMaxGeneratedVertices) + " vertices");
            p = makeSphere(radius, static_cast<uint32_t>(segments), material);
        } else if (d.kind == DeclKind::Plane) {
            std::vector<float> size = {10.0f, 10.0f};
            if (b.has("size")) RG_TRY(size, numbers(w.at("size"), b["size"], 2, "{width, depth} in metres", Range::positive()));
            p = makePlane(size[0], size[1], material);
        } else {
            glm::vec3 size(1.0f);
            RG_TRY(size, vec3(w, b, "size", size, "{x, y, z} in metres", Range::positive()));
            p = makeBox(size, material);
        }
        bool castShadows = true;
        RG_TRY(castShadows, boolean(w, b, "cast_shadows", true));
        generatedVertices += p.vertices.size();
        Mesh mesh;
        mesh.name = d.name;
        mesh.primitives.push_back(std::move(p));
        scene.nodes.push_back({d.name, world, static_cast<int32_t>(scene.meshes.size())});
        scene.nodes.back().castShadows = castShadows;
        scene.meshes.push_back(std::move(mesh));
        return {};
    }

    // Appends a loaded glTF scene, placed by `t`; names get the declaration's name in front.
    void merge(Scene&& sub, const glm::mat4& t, const std::string& prefix) {
        const auto matOff = static_cast<uint32_t>(scene.materials.size());
        const auto imgOff = static_cast<int32_t>(scene.images.size());
        const auto smpOff = static_cast<int32_t>(scene.samplers.size());
        const auto meshOff = static_cast<int32_t>(scene.meshes.size());
        for (auto& m : sub.materials) {
            for (TextureRef* tex : {&m.baseColorTex, &m.metallicRoughnessTex, &m.normalTex, &m.occlusionTex, &m.emissiveTex}) {
                if (tex->image >= 0) tex->image += imgOff;
                if (tex->sampler >= 0) tex->sampler += smpOff;
            }
            m.name = prefix + "/" + m.name;
            scene.materials.push_back(std::move(m));
        }
        for (auto& img : sub.images) scene.images.push_back(std::move(img));
        for (auto& s : sub.samplers) scene.samplers.push_back(s);
        for (auto& mesh : sub.meshes) {
            for (auto& p : mesh.primitives) p.material += matOff;
            mesh.name = prefix + "/" + mesh.name;
            scene.meshes.push_back(std::move(mesh));
        }
        for (auto& n : sub.nodes) scene.nodes.push_back({prefix + "/" + n.name, t * n.world, n.mesh + meshOff});
        const glm::mat3 linear(t);
        auto dir = [&](glm::vec3 v) {
            const glm::vec3 r = linear * v;
            return glm::length(r) > 0.0f ? glm::normalize(r) : v;
        };
        for (auto& l : sub.lights) {
            l.name = prefix + "/" + l.name;
            l.position = glm::vec3(t * glm::vec4(l.position, 1.0f));
            l.direction = dir(l.direction);
            l.up = dir(l.up);
            scene.lights.push_back(std::move(l));
        }
        for (auto& c : sub.cameras) {
            c.name = prefix + "/" + c.name;
            c.position = glm::vec3(t * glm::vec4(c.position, 1.0f));
            c.target = glm::vec3(t * glm::vec4(c.target, 1.0f));
            c.up = dir(c.up);
            scene.cameras.push_back(std::move(c));
        }
        if (sub.environment && !scene.environment) scene.environment = sub.environment;
        for (const auto& f : sub.files) addFile(f);
    }

    Result<void> gltf(const Declaration& d) {
        Where w = where(d);
        const Value& b = d.body;
        if (auto r = checkFields(w, b, {"file", "position", "rotation", "scale", "cast_shadows", "doc"}); !r) return r;
        if (!b.has("file")) return w.at("file").error("missing (expected a .gltf or .glb file, relative to the script)");
        if (!b["file"].isString()) return w.at("file").error("expected a file name, got " + describe(b["file"]));
        glm::mat4 t;
        RG_TRY(t, transform(w, b));
        GltfOptions go;
        go.loadImages = options.loadImages;
        go.generateMips = options.generateMips;
        bool castShadows = true;
        RG_TRY(castShadows, boolean(w, b, "cast_shadows", true));
        auto sub = loadGltf(resolve(b["file"].asString()), go);
        if (!sub) return fail(sub.error().code, d.origin + ": " + w.at("file").path + ": " + sub.error().message, sub.error().reasons);
        const size_t firstNode = scene.nodes.size();
        merge(std::move(*sub), t, d.name);
        if (!castShadows)
            for (size_t n = firstNode; n < scene.nodes.size(); ++n) scene.nodes[n].castShadows = false;
        return {};
    }

    Result<void> light(const Declaration& d) {
        Where w = where(d);
        const Value& b = d.body;
        if (auto r = checkFields(w, b, {"type", "intensity", "unit", "color", "temperature", "locus", "position", "direction", "target", "up", "baked",
                                        "radius", "width", "height", "length", "inner_angle", "outer_angle", "range", "ies",
                                        "ies_mode", "exact_cone", "angular_radius", "shadow", "doc"});
            !r)
            return r;
        Light l;
        l.name = d.name;
        if (!b.has("type")) return w.at("type").error("missing (expected one of: 'point', 'spot', 'sun', 'sphere', 'disk', 'rect', 'tube')");
        std::string type;
        RG_TRY(type, choice(w, b, "type", "", {"point", "spot", "sun", "directional", "sphere", "disk", "rect", "tube"}, "light type"));
        const std::map<std::string, LightType> types = {{"point", LightType::Point}, {"spot", LightType::Spot},
                                                        {"sun", LightType::Directional}, {"directional", LightType::Directional},
                                                        {"sphere", LightType::Sphere}, {"disk", LightType::Disk},
                                                        {"rect", LightType::Rect}, {"tube", LightType::Tube}};
        l.type = types.at(type);
        const bool punctual = l.type == LightType::Point || l.type == LightType::Spot;
        const bool sun = l.type == LightType::Directional;
        const std::string a = "a " + type + " light";

        // Which fields this type has (seed 000 §4.4-4.7).
        auto only = [&](const char* field, bool allowed, const std::string& who) -> Result<void> {
            if (b.has(field) && !allowed) return w.at(field).error("not used by " + a + " (only by " + who + ")");
            return {};
        };
        if (auto r = only("radius", l.type == LightType::Sphere || l.type == LightType::Disk || l.type == LightType::Tube,
                          "sphere, disk and tube lights"); !r) return r;
        if (auto r = only("width", l.type == LightType::Rect, "rect lights"); !r) return r;
        if (auto r = only("height", l.type == LightType::Rect, "rect lights"); !r) return r;
        if (auto r = only("up", l.type == LightType::Rect, "rect lights"); !r) return r;
        if (auto r = only("length", l.type == LightType::Tube, "tube lights"); !r) return r;
        if (auto r = only("inner_angle", l.type == LightType::Spot || l.type == LightType::Disk, "spot and disk lights"); !r) return r;
        if (auto r = only("outer_angle", l.type == LightType::Spot || l.type == LightType::Disk, "spot and disk lights"); !r) return r;
        if (l.type == LightType::Disk && b.has("inner_angle") && !b.has("outer_angle"))
            return w.at("inner_angle").error("a disk's cone needs its outer_angle too (seed 000 lst:9)");
        if (auto r = only("ies", punctual, "point and spot lights"); !r) return r;
        if (auto r = only("ies_mode", punctual, "point and spot lights with an IES profile"); !r) return r;
        if (b.has("ies_mode") && !b.has("ies")) return w.at("ies_mode").error("needs an ies profile to apply");
        if (auto r = only("exact_cone", l.type == LightType::Spot, "spot lights"); !r) return r;
        if (auto r = only("angular_radius", sun, "the sun"); !r) return r;
        if (auto r = only("range", !sun, "local lights"); !r) return r;
        if (auto r = only("shadow", !sun, "local lights; the sun's shadow is the pipeline's sun_shadows parameter"); !r) return r;
        if (auto r = only("direction", l.type != LightType::Sphere, "lights with an orientation"); !r) return r;
        if (auto r = only("target", l.type != LightType::Sphere, "lights with an orientation"); !r) return r;

        // Units: seed 000 tbl:8.
        std::vector<std::string> units = punctual ? std::vector<std::string>{"lm", "cd"}
                                         : sun    ? std::vector<std::string>{"lux"}
                                                  : std::vector<std::string>{"lm", "nits", "ev100"};
        RG_TRY(l.unit, string(w, b, "unit", units[0]));
        if (std::find(units.begin(), units.end(), l.unit) == units.end()) {
            const std::vector<std::string> all = {"lm", "cd", "lux", "nits", "ev100"};
            if (std::find(all.begin(), all.end(), l.unit) == all.end())
                return w.at("unit").error("unknown unit '" + l.unit + "'" + suggestion(l.unit, all) + "; " + a + " takes " + joinQuoted(units));
            return w.at("unit").error(a + " cannot be given in '" + l.unit + "' (seed 000 tbl:8); expected " + joinQuoted(units));
        }
        if (!b.has("intensity")) return w.at("intensity").error("missing (expected a number, in " + joinQuoted(units) + ")");
        RG_TRY(l.intensity, numberF(w, b, "intensity", 0.0f, l.unit == "ev100" ? Range::any() : Range::nonNegative()));

        if (b.has("color") && b.has("temperature")) return w.at("temperature").error("give either color or temperature, not both");
        RG_TRY(l.color, colour(w, b, "color", l.color, Range::nonNegative()));
        // The ranges lights::colorTemperatureXy converts: the black body 1667–25000 K, daylight 4000–25000 K.
        std::string locus;
        RG_TRY(locus, choice(w, b, "locus", "blackbody", {"blackbody", "daylight"}, "colour temperature locus"));
        if (b.has("locus") && !b.has("temperature")) return w.at("locus").error("applies with a temperature only");
        l.daylight = locus == "daylight";
        RG_TRY(l.temperatureK, numberF(w, b, "temperature", 0.0f,
                                       Range::closed(l.daylight ? lights::kMinDaylightTemperature : lights::kMinColorTemperature, lights::kMaxColorTemperature)));

        RG_TRY(l.position, vec3(w, b, "position", l.position));
        if (b.has("direction") && b.has("target")) return w.at("target").error("give either direction or target, not both");
        if (b.has("direction")) {
            glm::vec3 dir;
            RG_TRY(dir, vec3(w, b, "direction", l.direction));
            if (glm::length(dir) < 1e-6f) return w.at("direction").error("expected a non-zero vector, got {0, 0, 0}");
            l.direction = glm::normalize(dir);
        } else if (b.has("target")) {
            glm::vec3 target;
            RG_TRY(target, vec3(w, b, "target", glm::vec3(0.0f)));
            if (glm::length(target - l.position) < 1e-6f) return w.at("target").error("equals position; the light needs a direction");
            l.direction = glm::normalize(target - l.position);
        } else if (l.type != LightType::Point && l.type != LightType::Sphere)
            return w.at("direction").error("missing (" + a + " needs direction or target)");

        auto need = [&](const char* field, float& out) -> Result<void> {
            if (!b.has(field)) return w.at(field).error("missing (" + a + " needs its " + field + " in metres)");
            auto r = numberF(w, b, field, 0.0f, Range::positive());
            if (!r) return std::unexpected(r.error());
            out = *r;
            return {};
        };
        if (l.type == LightType::Sphere || l.type == LightType::Disk || l.type == LightType::Tube)
            if (auto r = need("radius", l.radius); !r) return r;
        if (l.type == LightType::Rect) {
            if (auto r = need("width", l.width); !r) return r;
            if (auto r = need("height", l.height); !r) return r;
            glm::vec3 up;
            RG_TRY(up, vec3(w, b, "up", l.up));
            if (glm::length(glm::cross(up, l.direction)) < 1e-6f)
                return w.at("up").error("is parallel to the light's direction (or zero); the rect needs a height axis");
            l.up = glm::normalize(up);
        }
        if (l.type == LightType::Tube)
            if (auto r = need("length", l.length); !r) return r;
        if (l.type == LightType::Spot || (l.type == LightType::Disk && b.has("outer_angle"))) {
            l.cone = l.type == LightType::Disk;
            float inner = 0.0f, outer = 45.0f;
            RG_TRY(inner, numberF(w, b, "inner_angle", inner, Range::closed(0, 90)));
            RG_TRY(outer, numberF(w, b, "outer_angle", outer, Range::openLow(0, 90)));
            if (inner > outer)
                return w.at("inner_angle").error("is " + formatNumber(inner) + "°, wider than outer_angle (" + formatNumber(outer) + "°)");
            l.innerAngle = inner * kDegrees;
            l.outerAngle = outer * kDegrees;
        }
        RG_TRY(l.range, numberF(w, b, "range", 0.0f, Range::nonNegative()));
        if (b.has("ies")) RG_TRY(l.ies, existingFile(w, b, "ies"));
        if (b.has("ies_mode")) RG_TRY(l.iesMode, choice(w, b, "ies_mode", "", {"mask", "intensity"}, "IES mode"));
        RG_TRY(l.exactCone, boolean(w, b, "exact_cone", false));
        RG_TRY(l.castShadows, boolean(w, b, "shadow", false));
        RG_TRY(l.baked, boolean(w, b, "baked", false));
        float angular = 0.2664f;
        RG_TRY(angular, numberF(w, b, "angular_radius", angular, Range::openLow(0, 10)));
        l.sunAngularRadius = angular * kDegrees;
        scene.lights.push_back(std::move(l));
        return {};
    }

    Result<void> camera(const Declaration& d) {
        Where w = where(d);
        const Value& b = d.body;
        if (auto r = checkFields(w, b, {"position", "target", "up", "fov", "focal_length", "sensor_height", "height", "aperture", "shutter",
                                        "iso", "ec", "near", "far", "doc"});
            !r)
            return r;
        Camera c;
        c.name = d.name;
        c.position = glm::vec3(0.0f, 1.0f, 5.0f);
        RG_TRY(c.position, vec3(w, b, "position", c.position));
        RG_TRY(c.target, vec3(w, b, "target", c.target));
        RG_TRY(c.up, vec3(w, b, "up", c.up));
        if (glm::length(c.target - c.position) < 1e-6f) return w.at("target").error("equals position; the camera needs a direction to look in");
        if (glm::length(glm::cross(c.up, c.target - c.position)) < 1e-6f * glm::length(c.target - c.position))
            return w.at("up").error("is parallel to the view direction (or zero); e.g. up = {0, 0, -1} for a camera looking straight down");
        if (b.has("fov") && b.has("focal_length")) return w.at("focal_length").error("give either fov or focal_length (with sensor_height), not both");
        if (b.has("sensor_height") && !b.has("focal_length")) return w.at("sensor_height").error("applies with focal_length only");
        float fovDeg = 45.0f;
        RG_TRY(fovDeg, numberF(w, b, "fov", fovDeg, Range::open(0, 180)));
        c.verticalFov = fovDeg * kDegrees;
        if (b.has("focal_length")) {
            float focalMm = 0.0f, sensorMm = 24.0f;
            RG_TRY(focalMm, numberF(w, b, "focal_length", focalMm, Range::positive()));
            RG_TRY(sensorMm, numberF(w, b, "sensor_height", sensorMm, Range::positive()));
            c.focalLength = focalMm / 1000.0f;
            c.sensorHeight = sensorMm / 1000.0f;
            c.verticalFov = 2.0f * std::atan(c.sensorHeight / (2.0f * c.focalLength));
        }
        // height = metres: an orthographic camera showing that much of the scene top to bottom.
        if (b.has("height")) {
            if (b.has("fov") || b.has("focal_length"))
                return w.at("height").error("an orthographic camera (height) has no fov or focal_length");
            RG_TRY(c.orthoHeight, numberF(w, b, "height", c.orthoHeight, Range::positive()));
            c.orthographic = true;
        }
        RG_TRY(c.aperture, numberF(w, b, "aperture", c.aperture, Range::closed(0.5, 128)));
        RG_TRY(c.shutter, numberF(w, b, "shutter", c.shutter, Range::openLow(0, 60)));
        RG_TRY(c.iso, numberF(w, b, "iso", c.iso, Range::closed(1, 1000000)));
        RG_TRY(c.exposureCompensation, numberF(w, b, "ec", c.exposureCompensation, Range::closed(-20, 20)));
        RG_TRY(c.nearPlane, numberF(w, b, "near", c.nearPlane, Range::positive()));
        RG_TRY(c.farPlane, numberF(w, b, "far", c.farPlane, Range::positive()));
        if (c.farPlane <= c.nearPlane)
            return w.at("far").error("is " + formatNumber(c.farPlane) + ", not beyond near (" + formatNumber(c.nearPlane) + ")");
        scene.cameras.push_back(c);
        return {};
    }

    Result<void> environment(const Declaration& d) {
        Where w = where(d);
        const Value& b = d.body;
        if (auto r = checkFields(w, b, {"kind", "file", "color", "intensity", "unit", "rotation", "turbidity", "doc"}); !r) return r;
        Environment e;
        e.name = d.name;
        if (!b.has("kind")) return w.at("kind").error("missing (expected one of: 'sky', 'hdr', 'color')");
        RG_TRY(e.kind, choice(w, b, "kind", "", {"sky", "hdr", "color"}, "environment kind"));
        if (b.has("file") && e.kind != "hdr") return w.at("file").error("applies to kind = \"hdr\" only");
        if (b.has("color") && e.kind != "color") return w.at("color").error("applies to kind = \"color\" only");
        if (b.has("turbidity") && e.kind != "sky") return w.at("turbidity").error("applies to kind = \"sky\" only");
        RG_TRY(e.turbidity, numberF(w, b, "turbidity", e.turbidity, Range::closed(1.7, 10)));
        if (e.kind == "hdr") {
            if (!b.has("file")) return w.at("file").error("missing (expected an equirectangular .hdr or .exr, relative to the script)");
            RG_TRY(e.file, existingFile(w, b, "file"));
        }
        RG_TRY(e.color, colour(w, b, "color", e.color, Range::nonNegative()));
        RG_TRY(e.intensity, numberF(w, b, "intensity", e.intensity, Range::nonNegative()));
        RG_TRY(e.unit, string(w, b, "unit", "nits"));
        if (e.unit != "nits") return w.at("unit").error("an environment's luminance is in 'nits' (seed 000 tbl:8), got '" + e.unit + "'");
        float rotation = 0.0f;
        RG_TRY(rotation, numberF(w, b, "rotation", rotation, Range::closed(-360, 360)));
        e.rotation = rotation * kDegrees;
        scene.environment = e;
        return {};
    }

    // scene.lightmap "name" { density, lobes, samples, bounces, max_size }
    Result<void> lightmap(const Declaration& d) {
        Where w = where(d);
        const Value& b = d.body;
        if (auto r = checkFields(w, b, {"density", "lobes", "samples", "bounces", "max_size", "doc"}); !r) return r;
        LightmapSettings s;
        s.name = d.name;
        s.origin = d.origin;
        RG_TRY(s.density, numberF(w, b, "density", s.density, Range::openLow(0, 1024)));
        double lobes = s.lobes;
        RG_TRY(lobes, number(w, b, "lobes", lobes, Range{1, 64, false, false, true}));
        if (lobes != 5 && lobes != 6 && lobes != 9 && lobes != 12)
            return w.at("lobes").error("expected 5, 6, 9 or 12 (seed 003 \"Light Map Data\"), got " + formatNumber(lobes));
        s.lobes = static_cast<int>(lobes);
        double samples = s.samples, bounces = s.bounces, maxSize = s.maxSize;
        RG_TRY(samples, number(w, b, "samples", samples, Range{1, 65536, false, false, true}));
        RG_TRY(bounces, number(w, b, "bounces", bounces, Range{1, 16, false, false, true}));
        RG_TRY(maxSize, number(w, b, "max_size", maxSize, Range{64, 4096, false, false, true}));  // 4096² × 13 layers is ~1.7 GiB on the GPU
        s.samples = static_cast<int>(samples);
        s.bounces = static_cast<int>(bounces);
        s.maxSize = static_cast<int>(maxSize);
        scene.lightmap = s;
        return {};
    }

    // scene.probe "name" { position, shape = "sphere" (radius) | "box" (size, rotation), fade, priority }
    Result<void> probe(const Declaration& d) {
        Where w = where(d);
        const Value& b = d.body;
        if (auto r = checkFields(w, b, {"position", "shape", "radius", "size", "rotation", "influence", "fade", "priority", "doc"}); !r) return r;
        if (scene.probes.size() >= kMaxProbes)
            return w.error("a scene has at most " + std::to_string(kMaxProbes) + " light probes (shaders/lib/probes.glsl RG_MAX_PROBES)");
        Probe p;
        p.name = d.name;
        p.origin = d.origin;
        std::string shape;
        RG_TRY(shape, choice(w, b, "shape", "sphere", {"sphere", "box"}, "probe shape"));
        p.box = shape == "box";
        if (p.box && b.has("radius")) return w.at("radius").error("a box probe has a size, not a radius");
        if (!p.box && (b.has("size") || b.has("rotation"))) return w.at(b.has("size") ? "size" : "rotation").error("a sphere probe has a radius (give shape = \"box\" for a size)");
        RG_TRY(p.position, vec3(w, b, "position", p.position));
        RG_TRY(p.radius, numberF(w, b, "radius", p.radius, Range::positive()));
        RG_TRY(p.size, vec3(w, b, "size", p.size, "{x, y, z} in metres", Range::positive()));
        glm::vec3 rotation(0.0f);
        RG_TRY(rotation, vec3(w, b, "rotation", rotation, "{x, y, z} in degrees"));
        glm::mat4 m(1.0f);
        m = glm::rotate(m, rotation.z * kDegrees, glm::vec3(0, 0, 1));
        m = glm::rotate(m, rotation.y * kDegrees, glm::vec3(0, 1, 0));
        m = glm::rotate(m, rotation.x * kDegrees, glm::vec3(1, 0, 0));
        p.rotation = glm::mat3(m);
        if (b.has("influence")) {
            if (p.box) RG_TRY(p.influenceSize, vec3(w, b, "influence", p.size, "{x, y, z} in metres (the box of influence)", Range::positive()));
            else RG_TRY(p.influenceRadius, numberF(w, b, "influence", p.radius, Range::positive()));
        }
        RG_TRY(p.fade, numberF(w, b, "fade", p.fade, Range::nonNegative()));
        float priority = 0.0f;
        RG_TRY(priority, numberF(w, b, "priority", priority, Range{-1000, 1000, false, false, true}));
        p.priority = static_cast<int>(priority);
        scene.probes.push_back(p);
        return {};
    }

    Result<void> decal(const Declaration& d) {
        Where w = where(d);
        const Value& b = d.body;
        if (auto r = checkFields(w, b, {"position", "rotation", "size", "opacity", "base_color", "smoothness", "metal_mask",
                                        "reflectance", "normal", "doc"});
            !r)
            return r;
        Decal decal;
        decal.name = d.name;
        glm::vec3 position, rotation, size(1.0f);
        RG_TRY(position, vec3(w, b, "position", glm::vec3(0.0f)));
        RG_TRY(rotation, vec3(w, b, "rotation", glm::vec3(0.0f), "{x, y, z} in degrees"));
        RG_TRY(size, vec3(w, b, "size", size, "{x, y, z} in metres", Range::positive()));
        glm::mat4 m = glm::translate(glm::mat4(1.0f), position);
        m = glm::rotate(m, rotation.z * kDegrees, glm::vec3(0, 0, 1));
        m = glm::rotate(m, rotation.y * kDegrees, glm::vec3(0, 1, 0));
        m = glm::rotate(m, rotation.x * kDegrees, glm::vec3(1, 0, 0));
        decal.world = glm::scale(m, size);
        RG_TRY(decal.opacity, numberF(w, b, "opacity", 1.0f, Range::unit()));
        decal.hasBaseColor = b.has("base_color");
        decal.hasSmoothness = b.has("smoothness");
        decal.hasMetalMask = b.has("metal_mask");
        decal.hasReflectance = b.has("reflectance");
        RG_TRY(decal.baseColor, colour(w, b, "base_color", decal.baseColor));
        RG_TRY(decal.smoothness, numberF(w, b, "smoothness", decal.smoothness, Range::unit()));
        RG_TRY(decal.metalMask, numberF(w, b, "metal_mask", decal.metalMask, Range::unit()));
        RG_TRY(decal.reflectance, numberF(w, b, "reflectance", decal.reflectance, Range::unit()));
        RG_TRY(decal.normal, boolean(w, b, "normal", false));
        scene.decals.push_back(decal);
        return {};
    }

    // A camera that sees the whole scene from the front, a little above.
    void defaultCamera() {
        Camera c;
        c.name = "default";
        const glm::vec3 centre = (scene.boundsMin + scene.boundsMax) * 0.5f;
        const float radius = std::max(0.5f * glm::length(scene.boundsMax - scene.boundsMin), 0.5f);
        const float distance = radius / std::sin(c.verticalFov * 0.5f) * 1.05f;
        c.target = centre;
        c.position = centre + glm::normalize(glm::vec3(0.0f, 0.45f, 1.0f)) * distance;
        c.nearPlane = std::max(0.01f, (distance - radius) * 0.5f);
        c.farPlane = std::max(1000.0f, (distance + radius) * 2.0f);
        scene.cameras.push_back(c);
    }

    Result<Scene> build(const std::vector<Declaration>& decls) {
        if (auto r = names(decls); !r) return std::unexpected(r.error());
        // Materials first, so objects may name a material declared further down.
        for (const auto& d : decls)
            if (d.kind == DeclKind::SceneMaterial)
                if (auto r = material(d); !r) return std::unexpected(r.error());
        for (const auto& d : decls) {
            Result<void> r;
            switch (d.kind) {
            case DeclKind::Sphere:
            case DeclKind::Plane:
            case DeclKind::Box: r = object(d); break;
            case DeclKind::Gltf: r = gltf(d); break;
            case DeclKind::Light: r = light(d); break;
            case DeclKind::Camera: r = camera(d); break;
            case DeclKind::Decal: r = decal(d); break;
            case DeclKind::Probe: r = probe(d); break;
            case DeclKind::Lightmap: r = lightmap(d); break;
            default: break;
            }
            if (!r) return std::unexpected(r.error());
        }
        for (const auto& d : decls)
            if (d.kind == DeclKind::Environment)
                if (auto r = environment(d); !r) return std::unexpected(r.error());
        if (options.generateMips)
            for (auto& img : scene.images)
                if (img.mips.empty() && img.pixels.width > 0) generateMips(img);
        computeBounds(scene);
        if (scene.cameras.empty()) defaultCamera();
        return std::move(scene);
    }
};

std::string defaultRoot() {
    if (const char* r = std::getenv("RG_ROOT"); r && *r) return r;
    return RG_SOURCE_ROOT;
}

}  // namespace

Result<Scene> loadSceneScript(const std::string& path, const SceneScriptOptions& options) {
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) {
        auto r = readFile(path);
        return fail(ErrorCode::NotFound, r ? "'" + path + "' is not a regular file" : "scene script: " + r.error().message);
    }
    const std::string root = options.projectRoot.empty() ? defaultRoot() : options.projectRoot;
    LuaHostOptions ho;
    ho.projectRoot = root;
    ho.searchDirs = {root + "/scripts", root + "/materials"};
    ho.sceneArgs = options.args;
    LuaHost host(ho);
    std::vector<std::string> files;
    auto decls = host.loadDeclarations(path, &files);
    if (!decls) return std::unexpected(decls.error());
    Builder b{path, options, {}, {}, {}, {}, nullptr, nullptr};
    for (const auto& f : files) b.addFile(f);
    return b.build(*decls);
}

}  // namespace rg

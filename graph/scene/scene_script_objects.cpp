// scene.material, scene.sphere/plane/box, scene.gltf and scene.decal -> the Scene's materials,
// meshes, nodes and decals (a glTF file's scene merged in, placed and renamed).
#include <algorithm>
#include <functional>

#include <glm/gtc/matrix_transform.hpp>

#include "lua/declarations.h"
#include "scene.h"
#include "scene_detail.h"
#include "scene_script_detail.h"

namespace rg {

using namespace scene_detail;

namespace scene_script {

Result<void> Builder::material(const Declaration& d) {
    Where w = where(d);
    const Value& b = d.body;
    if (auto r = checkFields(w, b, {"model",        "base_color",     "smoothness",
                                    "metal_mask",   "reflectance",    "ao",
                                    "emissive",     "emissive_unit",  "emissive_ec",
                                    "opacity",      "diffuse_color",  "f0",
                                    "params",       "double_sided",   "alpha",
                                    "alpha_cutoff", "base_color_map", "metallic_roughness_map",
                                    "normal_map",   "normal_scale",   "occlusion_map",
                                    "emissive_map", "textures",       "doc"});
        !r)
        return r;
    Material m;
    m.name = d.name;
    RG_TRY(m.model, string(w, b, "model", "standard"));
    const bool twoColour = m.model == "two_colour";
    if (twoColour) {
        for (const char* f : {"base_color", "metal_mask", "reflectance"})
            if (b.has(f))
                return w.at(f).error(
                    "not used by model 'two_colour', which takes diffuse_color and f0");
    } else {
        for (const char* f : {"diffuse_color", "f0"})
            if (b.has(f))
                return w.at(f).error(
                    "applies to model 'two_colour' only (this material's model is '" + m.model +
                    "')");
    }
    RG_TRY(m.baseColor, colour(w, b, "base_color", m.baseColor));
    RG_TRY(m.smoothness, numberF(w, b, "smoothness", m.smoothness, Range::unit()));
    RG_TRY(m.metalMask, numberF(w, b, "metal_mask", m.metalMask, Range::unit()));
    RG_TRY(m.reflectance, numberF(w, b, "reflectance", m.reflectance, Range::unit()));
    RG_TRY(m.ao, numberF(w, b, "ao", m.ao, Range::unit()));
    RG_TRY(m.opacity, numberF(w, b, "opacity", m.opacity, Range::unit()));
    RG_TRY(m.emissive, colour(w, b, "emissive", m.emissive, Range::nonNegative()));
    // "nits": emissive is luminance; "ev": a colour at emissive_ec stops relative to the exposure
    // (seed 002 §5.1.3: luminance = colour · 2^(EV100 + EC − 3)).
    std::string emissiveUnit;
    RG_TRY(emissiveUnit, choice(w, b, "emissive_unit", "nits", {"nits", "ev"}, "emissive unit"));
    m.emissiveEv = emissiveUnit == "ev";
    if (b.has("emissive_ec") && !m.emissiveEv)
        return w.at("emissive_ec").error("applies with emissive_unit = \"ev\" only");
    RG_TRY(m.emissiveEc, numberF(w, b, "emissive_ec", 0.0f, Range::closed(-16, 16)));
    RG_TRY(m.diffuseColor, colour(w, b, "diffuse_color", m.diffuseColor));
    RG_TRY(m.f0, colour(w, b, "f0", m.f0));
    if (b.has("params") && !b["params"].isTable() &&
        !(b["params"].isList() && b["params"].asList().empty()))
        return w.at("params").error("expected a table of named parameters, got " +
                                    describe(b["params"]));
    m.extra = b["params"];
    m.origin = d.origin + ": " + w.path;
    RG_TRY(m.doubleSided, boolean(w, b, "double_sided", false));
    std::string alpha;
    RG_TRY(alpha, choice(w, b, "alpha", "opaque", {"opaque", "mask", "blend"}, "alpha mode"));
    m.alphaMode = alpha == "mask"    ? AlphaMode::Mask
                  : alpha == "blend" ? AlphaMode::Blend
                                     : AlphaMode::Opaque;
    if (b.has("alpha_cutoff") && m.alphaMode != AlphaMode::Mask)
        return w.at("alpha_cutoff").error("applies to alpha = \"mask\" only");
    RG_TRY(m.alphaCutoff, numberF(w, b, "alpha_cutoff", m.alphaCutoff, Range::unit()));
    // Texture files (PNG or JPEG, relative to the script), as glTF's five maps: base colour and
    // emissive are sRGB, the others linear; each multiplies its factor.
    const std::pair<const char*, std::pair<TextureRef*, bool>> maps[] = {
        {"base_color_map", {&m.baseColorTex, true}},
        {"metallic_roughness_map", {&m.metallicRoughnessTex, false}},
        {"normal_map", {&m.normalTex, false}},
        {"occlusion_map", {&m.occlusionTex, false}},
        {"emissive_map", {&m.emissiveTex, true}}};
    for (const auto& [field, target] : maps)
        if (b.has(field)) RG_TRY(target.first->image, textureFile(w, b, field, target.second));
    // The model's own textures (rg.material's `textures`) by name: a file each, linear (its
    // surface function says what the channels mean); the names are checked against the model
    // when the pipeline is known.
    if (b.has("textures")) {
        const Value& t = b["textures"];
        if (!t.isTable() && !(t.isList() && t.asList().empty()))
            return w.at("textures")
                .error("expected a table of texture files by the names the model declares, got " +
                       describe(t));
        const Where tw = w.at("textures");
        for (const auto& [name, file] : t.asTable())
            RG_TRY(m.textures[name].image, textureFile(tw, t, name, false));
    }
    if (b.has("normal_scale") && !b.has("normal_map"))
        return w.at("normal_scale").error("applies with a normal_map only");
    RG_TRY(m.normalScale, numberF(w, b, "normal_scale", m.normalScale, Range::closed(0, 10)));
    materials[d.name] = static_cast<uint32_t>(scene.materials.size());
    materialNames.push_back(d.name);
    scene.materials.push_back(std::move(m));
    return {};
}

Result<uint32_t> Builder::materialRef(const Where& w, const Value& b) {
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
    if (!v.isString())
        return w.at("material").error("expected a material name, got " + describe(v));
    auto it = materials.find(v.asString());
    if (it == materials.end())
        return w.at("material")
            .error("unknown material '" + v.asString() + "'" +
                   suggestion(v.asString(), materialNames) +
                   (materialNames.empty() ? "; the scene declares no scene.material"
                                          : "; declared: " + joinQuoted(materialNames)));
    return it->second;
}

Result<void> Builder::object(const Declaration& d) {
    Where w = where(d);
    const Value& b = d.body;
    std::vector<std::string> fields = {"position",     "rotation", "scale", "material",
                                       "cast_shadows", "doc",      "path"};
    if (d.kind == DeclKind::Sphere)
        fields.insert(fields.end(), {"radius", "segments"});
    else
        fields.push_back("size");
    if (auto r = checkFields(w, b, fields); !r) return r;
    glm::mat4 world;
    RG_TRY(world, transform(w, b));
    uint32_t material = 0;
    RG_TRY(material, materialRef(w, b));
    // What the mesh is made from, and the mesh itself once made (shared by nodes declared alike).
    std::string key;
    std::function<Primitive()> make;
    if (d.kind == DeclKind::Sphere) {
        float radius = 0.5f;
        double segments = 48;
        RG_TRY(radius, numberF(w, b, "radius", radius, Range::positive()));
        Range seg = Range::closed(3, 1024);
        seg.integer = true;
        RG_TRY(segments, number(w, b, "segments", segments, seg));
        key = "sphere " + std::to_string(radius) + " " + std::to_string(segments);
        make = [=] { return makeSphere(radius, static_cast<uint32_t>(segments), material); };
    } else if (d.kind == DeclKind::Plane) {
        std::vector<float> size = {10.0f, 10.0f};
        if (b.has("size"))
            RG_TRY(size, numbers(w.at("size"), b["size"], 2, "{width, depth} in metres",
                                 Range::positive()));
        key = "plane " + std::to_string(size[0]) + " " + std::to_string(size[1]);
        make = [=] { return makePlane(size[0], size[1], material); };
    } else {
        glm::vec3 size(1.0f);
        RG_TRY(size, vec3(w, b, "size", size, "{x, y, z} in metres", Range::positive()));
        key = "box " + std::to_string(size.x) + " " + std::to_string(size.y) + " " +
              std::to_string(size.z);
        make = [=] { return makeBox(size, material); };
    }
    key += " material " + std::to_string(material);
    bool castShadows = true;
    RG_TRY(castShadows, boolean(w, b, "cast_shadows", true));
    auto [at, made] = generatedMeshes.emplace(key, static_cast<int32_t>(scene.meshes.size()));
    if (made) {
        Primitive p = make();
        if (generatedVertices + p.vertices.size() > kMaxGeneratedVertices) {
            generatedMeshes.erase(at);
            return w.error("the scene's generated meshes would have more than " +
                           std::to_string(kMaxGeneratedVertices) + " vertices");
        }
        generatedVertices += p.vertices.size();
        Mesh mesh;
        mesh.name = d.name;
        mesh.primitives.push_back(std::move(p));
        scene.meshes.push_back(std::move(mesh));
    }
    scene.nodes.push_back({d.name, world, at->second});
    scene.nodes.back().castShadows = castShadows;
    return nodePath(w, b, scene.nodes.size() - 1);
}

// Appends a loaded glTF scene, placed by `t`; names get the declaration's name in front.
void Builder::merge(Scene&& sub, const glm::mat4& t, const std::string& prefix) {
    scene.warnings.insert(scene.warnings.end(), sub.warnings.begin(), sub.warnings.end());
    const auto matOff = static_cast<uint32_t>(scene.materials.size());
    const auto imgOff = static_cast<int32_t>(scene.images.size());
    const auto smpOff = static_cast<int32_t>(scene.samplers.size());
    const auto meshOff = static_cast<int32_t>(scene.meshes.size());
    for (auto& m : sub.materials) {
        for (TextureRef* tex : m.textureRefs()) {
            if (tex->image >= 0) tex->image += imgOff;
            if (tex->sampler >= 0) tex->sampler += smpOff;
        }
        m.name = prefix + "/" + m.name;
        scene.materials.push_back(std::move(m));
    }
    for (auto& img : sub.images) scene.images.push_back(std::move(img));
    for (auto& s : sub.samplers) scene.samplers.push_back(s);
    for (auto& mesh : sub.meshes) {
        for (auto* list : {&mesh.primitives, &mesh.lines, &mesh.points})
            for (auto& p : *list) p.material += matOff;
        mesh.name = prefix + "/" + mesh.name;
        scene.meshes.push_back(std::move(mesh));
    }
    for (auto& n : sub.nodes) {
        Node& node = scene.nodes.emplace_back(std::move(n));
        node.name = prefix + "/" + node.name;
        node.world = t * node.world;
        node.mesh += meshOff;
        node.animationPlacement = t * node.animationPlacement;
    }
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

Result<void> Builder::gltf(const Declaration& d) {
    Where w = where(d);
    const Value& b = d.body;
    if (auto r = checkFields(w, b,
                             {"file", "position", "rotation", "scale", "cast_shadows", "variant",
                              "animation", "path", "doc"});
        !r)
        return r;
    if (!b.has("file"))
        return w.at("file").error(
            "missing (expected a .gltf or .glb file, relative to the script)");
    if (!b["file"].isString())
        return w.at("file").error("expected a file name, got " + describe(b["file"]));
    glm::mat4 t;
    RG_TRY(t, transform(w, b));
    GltfOptions go;
    go.loadImages = options.loadImages;
    go.generateMips = options.generateMips;
    go.buildLods = false;  // the script's end builds them for every mesh
    RG_TRY(go.variant, string(w, b, "variant", ""));
    RG_TRY(go.animation, string(w, b, "animation", ""));
    bool castShadows = true;
    RG_TRY(castShadows, boolean(w, b, "cast_shadows", true));
    auto sub = loadGltf(resolve(b["file"].asString()), go);
    if (!sub)
        return fail(sub.error().code,
                    d.origin + ": " + w.at("file").path + ": " + sub.error().message,
                    sub.error().reasons);
    const size_t firstNode = scene.nodes.size();
    merge(std::move(*sub), t, d.name);
    if (!castShadows)
        for (size_t n = firstNode; n < scene.nodes.size(); ++n) scene.nodes[n].castShadows = false;
    return nodePath(w, b, firstNode);
}

Result<void> Builder::decal(const Declaration& d) {
    Where w = where(d);
    const Value& b = d.body;
    if (auto r = checkFields(w, b,
                             {"position", "rotation", "size", "opacity", "base_color", "smoothness",
                              "metal_mask", "reflectance", "normal", "doc"});
        !r)
        return r;
    Decal decal;
    decal.name = d.name;
    glm::vec3 position, rotation, size(1.0f);
    RG_TRY(position, vec3(w, b, "position", glm::vec3(0.0f)));
    RG_TRY(rotation, vec3(w, b, "rotation", glm::vec3(0.0f), "{x, y, z} in degrees"));
    RG_TRY(size, vec3(w, b, "size", size, "{x, y, z} in metres", Range::positive()));
    decal.world = glm::scale(placement(position, rotation * kDegrees), size);
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

}  // namespace scene_script

}  // namespace rg

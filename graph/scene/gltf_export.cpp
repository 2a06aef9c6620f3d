// Scene -> binary glTF (.glb) with tinygltf's writer. Everything lives in one buffer (the GLB's
// binary chunk): vertex data, uint32 indices and the images as PNG. What glTF cannot say goes
// into `extras.rgraph` of the material / camera / light / scene, which loadGltf reads back.
#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <sstream>
#include <unistd.h>

#include <glm/gtc/matrix_transform.hpp>

#include "scene.h"
#include "core/light_units.h"
#include "scene_detail.h"
#include "tinygltf.h"
#include "core/temp_path.h"

namespace fs = std::filesystem;

namespace rg {

using namespace scene_detail;

namespace {

tinygltf::Value jsonOf(const Value& v) {
    if (v.isBool()) return tinygltf::Value(v.asBool());
    if (v.isNumber()) return tinygltf::Value(v.asNumber());
    if (v.isString()) return tinygltf::Value(v.asString());
    if (v.isList()) {
        tinygltf::Value::Array a;
        for (const auto& e : v.asList()) a.push_back(jsonOf(e));
        return tinygltf::Value(std::move(a));
    }
    if (v.isTable()) {
        tinygltf::Value::Object o;
        for (const auto& [k, e] : v.asTable()) o[k] = jsonOf(e);
        return tinygltf::Value(std::move(o));
    }
    return tinygltf::Value();
}

tinygltf::Value jsonOf(glm::vec3 v) {
    return tinygltf::Value(tinygltf::Value::Array{
        tinygltf::Value(double(v.x)), tinygltf::Value(double(v.y)), tinygltf::Value(double(v.z))});
}

std::vector<double> matrixOf(const glm::mat4& m) {
    std::vector<double> out(16);
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) out[size_t(c * 4 + r)] = double(m[c][r]);
    return out;
}

// A rotation whose local -Z is `dir` (and whose +Y is as close to `up` as it can be).
glm::mat4 orientation(glm::vec3 position, glm::vec3 dir, glm::vec3 up) {
    const glm::vec3 z = -glm::normalize(dir);
    glm::vec3 x = glm::cross(up, z);
    if (glm::length(x) < 1e-6f)
        x = glm::cross(std::fabs(z.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0), z);
    x = glm::normalize(x);
    const glm::vec3 y = glm::cross(z, x);
    glm::mat4 m(1.0f);
    m[0] = glm::vec4(x, 0);
    m[1] = glm::vec4(y, 0);
    m[2] = glm::vec4(z, 0);
    m[3] = glm::vec4(position, 1);
    return m;
}

struct Writer {
    const Scene& scene;
    std::vector<std::string>* warnings;
    tinygltf::Model model;
    std::vector<int> images;                      // Scene image -> glTF image (-1: not written)
    std::map<std::pair<int, int>, int> textures;  // (glTF image, glTF sampler) -> glTF texture
    bool usesTransform = false, usesStrength = false;
    std::filesystem::path
        outDir;  // the .glb's folder: files the scene names are written relative to it

    // A file the scene names (an IES profile, an environment image) as the .glb will name it:
    // relative to the .glb's folder (the loader resolves it from there), so no machine path is kept.
    std::string relativeName(const std::string& file) const {
        if (file.empty() || outDir.empty()) return file;
        std::error_code ec;
        const auto rel = std::filesystem::absolute(file, ec).lexically_relative(outDir);
        return ec || rel.empty() ? file : rel.generic_string();
    }

    void warn(const std::string& msg) {
        if (warnings) warnings->push_back(msg);
    }

    tinygltf::Buffer& buffer() { return model.buffers[0]; }

    int addView(const void* data, size_t size, int target) {
        auto& b = buffer().data;
        while (b.size() % 4) b.push_back(0);
        tinygltf::BufferView v;
        v.buffer = 0;
        v.byteOffset = b.size();
        v.byteLength = size;
        v.target = target;
        const auto* p = static_cast<const unsigned char*>(data);
        b.insert(b.end(), p, p + size);
        model.bufferViews.push_back(v);
        return int(model.bufferViews.size() - 1);
    }

    template <int N>
    int addFloats(const std::vector<float>& data, int type, bool bounds) {
        tinygltf::Accessor a;
        a.bufferView =
            addView(data.data(), data.size() * sizeof(float), TINYGLTF_TARGET_ARRAY_BUFFER);
        a.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
        a.type = type;
        a.count = data.size() / N;
        if (bounds && a.count > 0) {
            a.minValues.assign(N, 1e300);
            a.maxValues.assign(N, -1e300);
            for (size_t i = 0; i < a.count; ++i)
                for (int c = 0; c < N; ++c) {
                    a.minValues[size_t(c)] =
                        std::min(a.minValues[size_t(c)], double(data[i * N + size_t(c)]));
                    a.maxValues[size_t(c)] =
                        std::max(a.maxValues[size_t(c)], double(data[i * N + size_t(c)]));
                }
        }
        model.accessors.push_back(a);
        return int(model.accessors.size() - 1);
    }

    void samplers() {
        for (const auto& s : scene.samplers) {
            tinygltf::Sampler g;
            g.magFilter = s.magFilter == Filter::Nearest ? TINYGLTF_TEXTURE_FILTER_NEAREST
                                                         : TINYGLTF_TEXTURE_FILTER_LINEAR;
            const bool nearest = s.minFilter == Filter::Nearest,
                       mipNearest = s.mipmapMode == MipmapMode::Nearest;
            g.minFilter = nearest ? (mipNearest ? TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_NEAREST
                                                : TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_LINEAR)
                                  : (mipNearest ? TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_NEAREST
                                                : TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_LINEAR);
            auto wrap = [](Wrap w) {
                return w == Wrap::ClampToEdge      ? TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE
                       : w == Wrap::MirroredRepeat ? TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT
                                                   : TINYGLTF_TEXTURE_WRAP_REPEAT;
            };
            g.wrapS = wrap(s.wrapS);
            g.wrapT = wrap(s.wrapT);
            model.samplers.push_back(g);
        }
    }

    Result<void> writeImages() {
        for (size_t i = 0; i < scene.images.size(); ++i) {
            const SceneImage& img = scene.images[i];
            if (img.pixels.width == 0 || img.pixels.height == 0) {
                warn("image '" + img.name +
                     "' has no pixels (not loaded); textures using it are not exported");
                images.push_back(-1);
                continue;
            }
            auto png = encodePng(img.pixels);
            if (!png)
                return fail(png.error().code, "image '" + img.name + "': " + png.error().message);
            tinygltf::Image g;
            g.name = img.name;
            g.mimeType = "image/png";
            g.bufferView = addView(png->data(), png->size(), 0);
            model.images.push_back(g);
            images.push_back(int(model.images.size() - 1));
        }
        return {};
    }

    // -1 when the reference is empty or its image was not written.
    int textureOf(const TextureRef& ref) {
        if (ref.image < 0 || size_t(ref.image) >= images.size() || images[size_t(ref.image)] < 0)
            return -1;
        const int sampler =
            ref.sampler >= 0 && size_t(ref.sampler) < scene.samplers.size() ? ref.sampler : -1;
        auto key = std::make_pair(images[size_t(ref.image)], sampler);
        if (auto it = textures.find(key); it != textures.end()) return it->second;
        tinygltf::Texture t;
        t.source = key.first;
        t.sampler = sampler;
        model.textures.push_back(t);
        return textures[key] = int(model.textures.size() - 1);
    }

    // texCoord and KHR_texture_transform (the matrix is T * R * S without shear, see scene.h).
    template <class Info>
    void fillInfo(Info& info, const TextureRef& ref, int texture) {
        info.index = texture;
        info.texCoord = int(ref.texCoord);
        if (ref.transform == glm::mat3(1.0f)) return;
        const glm::vec2 c0(ref.transform[0]), c1(ref.transform[1]);
        const float sx = glm::length(c0), sy = glm::length(c1);
        const float rotation = std::atan2(-c0.y, c0.x);
        tinygltf::Value::Object t;
        t["offset"] =
            tinygltf::Value(tinygltf::Value::Array{tinygltf::Value(double(ref.transform[2].x)),
                                                   tinygltf::Value(double(ref.transform[2].y))});
        t["rotation"] = tinygltf::Value(double(rotation));
        t["scale"] = tinygltf::Value(
            tinygltf::Value::Array{tinygltf::Value(double(sx)), tinygltf::Value(double(sy))});
        info.extensions["KHR_texture_transform"] = tinygltf::Value(std::move(t));
        usesTransform = true;
    }

    void materials() {
        for (const auto& m : scene.materials) {
            tinygltf::Material g;
            g.name = m.name;
            auto& pbr = g.pbrMetallicRoughness;
            pbr.baseColorFactor = {m.baseColor.r, m.baseColor.g, m.baseColor.b, m.opacity};
            pbr.metallicFactor = m.metalMask;
            pbr.roughnessFactor = 1.0 - double(m.smoothness);
            // Nits -> emissiveFactor in [0, 1] × KHR_materials_emissive_strength.
            const float peak = std::max({m.emissive.r, m.emissive.g, m.emissive.b});
            if (peak > 1.0f) {
                g.emissiveFactor = {m.emissive.r / peak, m.emissive.g / peak, m.emissive.b / peak};
                g.extensions["KHR_materials_emissive_strength"] = tinygltf::Value(
                    tinygltf::Value::Object{{"emissiveStrength", tinygltf::Value(double(peak))}});
                usesStrength = true;
            } else
                g.emissiveFactor = {m.emissive.r, m.emissive.g, m.emissive.b};
            if (int t = textureOf(m.baseColorTex); t >= 0)
                fillInfo(pbr.baseColorTexture, m.baseColorTex, t);
            if (int t = textureOf(m.metallicRoughnessTex); t >= 0)
                fillInfo(pbr.metallicRoughnessTexture, m.metallicRoughnessTex, t);
            if (int t = textureOf(m.normalTex); t >= 0) fillInfo(g.normalTexture, m.normalTex, t);
            if (int t = textureOf(m.occlusionTex); t >= 0)
                fillInfo(g.occlusionTexture, m.occlusionTex, t);
            if (int t = textureOf(m.emissiveTex); t >= 0)
                fillInfo(g.emissiveTexture, m.emissiveTex, t);
            g.normalTexture.scale = m.normalScale;
            g.occlusionTexture.strength = m.occlusionStrength;
            g.alphaMode = m.alphaMode == AlphaMode::Mask    ? "MASK"
                          : m.alphaMode == AlphaMode::Blend ? "BLEND"
                                                            : "OPAQUE";
            g.alphaCutoff = m.alphaCutoff;
            g.doubleSided = m.doubleSided;
            tinygltf::Value::Object x;
            x["model"] = tinygltf::Value(m.model);
            x["reflectance"] = tinygltf::Value(double(m.reflectance));
            x["ao"] = tinygltf::Value(double(m.ao));
            x["diffuse_color"] = jsonOf(m.diffuseColor);
            x["f0"] = jsonOf(m.f0);
            // The emissive's unit (a reader other than rgraph takes glTF's: relative to exposure).
            x["emissive_unit"] = tinygltf::Value(std::string(m.emissiveEv ? "ev" : "nits"));
            if (m.emissiveEv) x["emissive_ec"] = tinygltf::Value(double(m.emissiveEc));
            if (!m.extra.isNil()) x["params"] = jsonOf(m.extra);
            // The model's own textures, as textureInfo objects by name (and whether the image is
            // sRGB-encoded, which the name does not say).
            tinygltf::Value::Object own;
            for (const auto& [name, ref] : m.textures)
                if (int t = textureOf(ref); t >= 0) {
                    tinygltf::TextureInfo info;
                    fillInfo(info, ref, t);
                    tinygltf::Value::Object o{
                        {"index", tinygltf::Value(info.index)},
                        {"texCoord", tinygltf::Value(info.texCoord)},
                        {"srgb", tinygltf::Value(scene.images[size_t(ref.image)].srgb)}};
                    if (!info.extensions.empty())
                        o["extensions"] = tinygltf::Value(tinygltf::Value::Object(
                            info.extensions.begin(), info.extensions.end()));
                    own[name] = tinygltf::Value(std::move(o));
                }
            if (!own.empty()) x["textures"] = tinygltf::Value(std::move(own));
            g.extras =
                tinygltf::Value(tinygltf::Value::Object{{"rgraph", tinygltf::Value(std::move(x))}});
            model.materials.push_back(g);
        }
    }

    void meshes() {
        for (const auto& mesh : scene.meshes) {
            tinygltf::Mesh g;
            g.name = mesh.name;
            // Triangles, then the lines and points (as LINES and POINTS).
            const std::pair<const std::vector<Primitive>*, int> lists[] = {
                {&mesh.primitives, TINYGLTF_MODE_TRIANGLES},
                {&mesh.lines, TINYGLTF_MODE_LINE},
                {&mesh.points, TINYGLTF_MODE_POINTS}};
            for (const auto& [list, mode] : lists)
                for (const auto& p : *list) {
                    std::vector<float> pos, nrm, tan, uv0, uv1, color;
                    bool hasUv1 = false, hasColor = false;
                    for (const auto& v : p.vertices) {
                        pos.insert(pos.end(), {v.position.x, v.position.y, v.position.z});
                        nrm.insert(nrm.end(), {v.normal.x, v.normal.y, v.normal.z});
                        tan.insert(tan.end(), {v.tangent.x, v.tangent.y, v.tangent.z, v.tangent.w});
                        uv0.insert(uv0.end(), {v.uv0.x, v.uv0.y});
                        uv1.insert(uv1.end(), {v.uv1.x, v.uv1.y});
                        hasUv1 = hasUv1 || v.uv1 != glm::vec2(0.0f);
                        for (int k = 0; k < 4; ++k) color.push_back(float(v.color[k]) / 65535.0f);
                        hasColor = hasColor || v.color != glm::u16vec4(65535);
                    }
                    tinygltf::Primitive gp;
                    gp.mode = mode;
                    gp.material = int(p.material);
                    gp.attributes["POSITION"] = addFloats<3>(pos, TINYGLTF_TYPE_VEC3, true);
                    gp.attributes["NORMAL"] = addFloats<3>(nrm, TINYGLTF_TYPE_VEC3, false);
                    gp.attributes["TANGENT"] = addFloats<4>(tan, TINYGLTF_TYPE_VEC4, false);
                    gp.attributes["TEXCOORD_0"] = addFloats<2>(uv0, TINYGLTF_TYPE_VEC2, false);
                    if (hasUv1)
                        gp.attributes["TEXCOORD_1"] = addFloats<2>(uv1, TINYGLTF_TYPE_VEC2, false);
                    if (hasColor)
                        gp.attributes["COLOR_0"] = addFloats<4>(color, TINYGLTF_TYPE_VEC4, false);
                    tinygltf::Accessor ia;
                    ia.bufferView = addView(p.indices.data(), p.indices.size() * sizeof(uint32_t),
                                            TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
                    ia.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
                    ia.type = TINYGLTF_TYPE_SCALAR;
                    ia.count = p.indices.size();
                    model.accessors.push_back(ia);
                    gp.indices = int(model.accessors.size() - 1);
                    g.primitives.push_back(gp);
                }
            model.meshes.push_back(g);
        }
    }

    void nodes(tinygltf::Scene& root) {
        for (const auto& n : scene.nodes) {
            tinygltf::Node g;
            g.name = n.name;
            g.mesh = n.mesh;
            if (n.world != glm::mat4(1.0f)) g.matrix = matrixOf(n.world);
            model.nodes.push_back(g);
            root.nodes.push_back(int(model.nodes.size() - 1));
        }
        for (const auto& c : scene.cameras) {
            tinygltf::Camera g;
            g.name = c.name;
            if (c.orthographic) {
                // glTF wants xmag too: the aspect is the render's, so 1:1 here (rgraph reads ymag).
                g.type = "orthographic";
                g.orthographic.xmag = g.orthographic.ymag = 0.5 * c.orthoHeight;
                g.orthographic.znear = c.nearPlane;
                g.orthographic.zfar = c.farPlane;
            } else {
                g.type = "perspective";
                g.perspective.yfov = c.verticalFov;
                g.perspective.znear = c.nearPlane;
                g.perspective.zfar = c.farPlane;
            }
            tinygltf::Value::Object x;
            x["aperture"] = tinygltf::Value(double(c.aperture));
            x["shutter"] = tinygltf::Value(double(c.shutter));
            x["iso"] = tinygltf::Value(double(c.iso));
            x["ec"] = tinygltf::Value(double(c.exposureCompensation));
            x["focal_length"] = tinygltf::Value(double(c.focalLength));
            x["sensor_height"] = tinygltf::Value(double(c.sensorHeight));
            x["target"] = jsonOf(c.target);
            x["up"] = jsonOf(c.up);
            g.extras =
                tinygltf::Value(tinygltf::Value::Object{{"rgraph", tinygltf::Value(std::move(x))}});
            model.cameras.push_back(g);
            tinygltf::Node node;
            node.name = c.name;
            node.camera = int(model.cameras.size() - 1);
            node.matrix = matrixOf(orientation(c.position, c.target - c.position, c.up));
            model.nodes.push_back(node);
            root.nodes.push_back(int(model.nodes.size() - 1));
        }
        for (const auto& l : scene.lights) {
            if (l.fromEnvironment) continue;  // the environment's sun: taken out again on load
            const bool punctual = l.type == LightType::Point || l.type == LightType::Spot;
            // Lumens become the candela rgraph renders them with (tbl:9: Φ/4π; spots eq:17: Φ/π),
            // so the exported file lights the same.
            const bool maps = (punctual && (l.unit == "cd" || l.unit == "lm")) ||
                              (l.type == LightType::Directional && l.unit == "lux");
            if (!maps) {
                warn("light '" + l.name + "' (" + lightTypeName(l.type) + ", " + l.unit +
                     ") is not exported: KHR_lights_punctual has " +
                     (punctual ? "point and spot lights in cd (or lm, converted) only"
                      : l.type == LightType::Directional ? "directional lights in lux only"
                                                         : "no area lights"));
                continue;
            }
            tinygltf::Light g;
            g.name = l.name;
            g.type = l.type == LightType::Point  ? "point"
                     : l.type == LightType::Spot ? "spot"
                                                 : "directional";
            g.color = {l.color.r, l.color.g, l.color.b};
            g.intensity =
                l.unit != "lm" ? l.intensity
                : l.type == LightType::Point
                    ? lights::pointIntensityFromLumens(l.intensity)
                    : lights::spotIntensityFromLumens(l.intensity, l.outerAngle, l.exactCone);
            g.range = l.range;
            g.spot.innerConeAngle = l.innerAngle;
            g.spot.outerConeAngle = l.outerAngle;
            tinygltf::Value::Object x;
            if (l.temperatureK > 0) x["temperature"] = tinygltf::Value(double(l.temperatureK));
            if (l.unit == "lm") x["lumens"] = tinygltf::Value(double(l.intensity));  // as declared
            if (!l.ies.empty()) x["ies"] = tinygltf::Value(relativeName(l.ies));
            if (!l.iesMode.empty()) x["ies_mode"] = tinygltf::Value(l.iesMode);
            if (l.exactCone) x["exact_cone"] = tinygltf::Value(true);
            if (l.castShadows) x["shadow"] = tinygltf::Value(true);
            if (l.type == LightType::Directional)
                x["angular_radius"] = tinygltf::Value(double(l.sunAngularRadius));
            if (!x.empty())
                g.extras = tinygltf::Value(
                    tinygltf::Value::Object{{"rgraph", tinygltf::Value(std::move(x))}});
            model.lights.push_back(g);
            tinygltf::Node node;
            node.name = l.name;
            node.matrix = matrixOf(orientation(l.position, l.direction, glm::vec3(0, 1, 0)));
            node.extensions["KHR_lights_punctual"] = tinygltf::Value(
                tinygltf::Value::Object{{"light", tinygltf::Value(int(model.lights.size() - 1))}});
            model.nodes.push_back(node);
            root.nodes.push_back(int(model.nodes.size() - 1));
        }
        if (scene.environment) {
            const Environment& e = *scene.environment;
            tinygltf::Value::Object x;
            x["name"] = tinygltf::Value(e.name);
            x["kind"] = tinygltf::Value(e.kind);
            x["file"] = tinygltf::Value(relativeName(e.file));
            x["color"] = jsonOf(e.color);
            x["intensity"] = tinygltf::Value(double(e.intensity));
            x["unit"] = tinygltf::Value(e.unit);
            x["rotation"] = tinygltf::Value(double(e.rotation));
            x["turbidity"] = tinygltf::Value(double(e.turbidity));
            x["sun"] = tinygltf::Value(e.sun);
            root.extras = tinygltf::Value(tinygltf::Value::Object{
                {"rgraph", tinygltf::Value(tinygltf::Value::Object{
                               {"environment", tinygltf::Value(std::move(x))}})}});
        }
    }

    Result<std::string> run() {
        model.asset.version = "2.0";
        model.asset.generator = "rgraph";
        model.buffers.emplace_back();
        samplers();
        if (auto r = writeImages(); !r) return std::unexpected(r.error());
        materials();
        meshes();
        tinygltf::Scene root;
        root.name = "scene";
        nodes(root);
        model.scenes.push_back(root);
        model.defaultScene = 0;
        if (usesTransform) model.extensionsUsed.push_back("KHR_texture_transform");
        if (usesStrength) model.extensionsUsed.push_back("KHR_materials_emissive_strength");
        if (buffer().data.empty()) model.buffers.clear();
        std::ostringstream out;
        tinygltf::TinyGLTF gltf;
        if (!gltf.WriteGltfSceneToStream(&model, out, /*prettyPrint=*/false, /*writeBinary=*/true))
            return fail(ErrorCode::Io, "tinygltf could not serialise the scene");
        return out.str();
    }
};

}  // namespace

Result<void> exportGlb(const Scene& scene, const std::string& path,
                       std::vector<std::string>* warnings) {
    Writer w{scene, warnings, {}, {}, {}, false, false, {}};
    std::error_code dirError;
    w.outDir = std::filesystem::absolute(std::filesystem::path(path).parent_path(), dirError)
                   .lexically_normal();
    auto bytes = w.run();
    if (!bytes) return fail(bytes.error().code, quote(path) + ": " + bytes.error().message);
    // Write beside the target and rename: a failed write never leaves half a file at `path`.
    const std::string temp = tempPathBeside(path);
    std::FILE* f = std::fopen(temp.c_str(), "wb");
    if (!f) return fail(ErrorCode::Io, "cannot write " + quote(path) + ": " + errnoText(errno));
    const bool written = std::fwrite(bytes->data(), 1, bytes->size(), f) == bytes->size();
    const int writeErr = errno;
    const bool closed = std::fclose(f) == 0;
    if (!written || !closed) {
        std::remove(temp.c_str());
        return fail(ErrorCode::Io,
                    "cannot write " + quote(path) + ": " + errnoText(written ? errno : writeErr));
    }
    std::error_code ec;
    fs::rename(temp, path, ec);
    if (ec) {
        std::remove(temp.c_str());
        return fail(ErrorCode::Io, "cannot write " + quote(path) + ": " + ec.message());
    }
    return {};
}

}  // namespace rg

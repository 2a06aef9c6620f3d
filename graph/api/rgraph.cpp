// The library's public interface (include/rgraph/rgraph.h) over the runtime the command line
// uses: a Runtime (its own device or the host's), a Session per loaded pipeline, scenes from
// files or from code, parameters and pass toggles applied as rg.frame's changes are.
#include "rgraph/rgraph.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

#include <glm/glm.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "core/light_units.h"
#include "runtime/runtime.h"
#include "runtime/session.h"
#include "image/image.h"
#include "scene/mesh_lod.h"
#include "scene/scene.h"
#include "scene/scene_detail.h"

namespace rgraph {

namespace fs = std::filesystem;

namespace {

[[noreturn]] void raise(const rg::Error& e) { throw Error(e.describe()); }

template <typename T>
T check(rg::Result<T> r) {
    if (!r) raise(r.error());
    if constexpr (!std::is_void_v<T>) return std::move(*r);
}

Image toImage(const rg::Image& i) { return {i.width, i.height, i.channels, i.pixels}; }
rg::Image fromImage(const Image& i) {
    rg::Image out(i.width, i.height, i.channels);
    if (i.pixels.size() != out.pixels.size())
        throw Error("image: " + std::to_string(i.pixels.size()) + " floats for " +
                    std::to_string(i.width) + "x" + std::to_string(i.height) + "x" +
                    std::to_string(i.channels));
    out.pixels = i.pixels;
    return out;
}

Mesh fromPrimitive(const std::string& name, const rg::Primitive& p) {
    Mesh m;
    m.name = name;
    for (const rg::Vertex& v : p.vertices) {
        m.positions.insert(m.positions.end(), {v.position.x, v.position.y, v.position.z});
        m.normals.insert(m.normals.end(), {v.normal.x, v.normal.y, v.normal.z});
        m.uvs.insert(m.uvs.end(), {v.uv0.x, v.uv0.y});
    }
    m.indices = p.indices;
    for (const rg::PrimitiveLod& lod : p.lods) m.lods.push_back({lod.indices, lod.error});
    return m;
}

glm::vec3 vec3(const float* v) { return {v[0], v[1], v[2]}; }

// A material's texture file (scene_detail::textureFile, decoded once per file and encoding): its
// index in scene.images, with its mips.
int32_t textureFile(rg::Scene& s, const std::string& where, const std::string& file, bool srgb) {
    auto index =
        rg::scene_detail::textureFile(s, fs::absolute(file).lexically_normal().string(), srgb);
    if (!index) throw Error(where + ": " + index.error().message);
    rg::SceneImage& image = s.images[static_cast<size_t>(*index)];
    if (image.mips.empty()) rg::generateMips(image);
    return *index;
}

// The host's scene as rgraph's: meshes with tangents generated, materials by name, lights in
// the units they say, the camera; checked as a Lua scene's fields are.
rg::Scene toScene(const Scene& in) {
    rg::Scene s;
    std::map<std::string, uint32_t> materials;
    for (const Material& m : in.materials) {
        if (materials.count(m.name))
            throw Error("scene.materials: two materials named '" + m.name + "'");
        rg::Material r;
        r.name = m.name;
        r.model = m.model;
        r.baseColor = vec3(m.baseColor);
        r.smoothness = m.smoothness;
        r.metalMask = m.metalMask;
        r.reflectance = m.reflectance;
        r.ao = m.ao;
        r.emissive = vec3(m.emissive);
        r.opacity = m.opacity;
        r.alphaMode = m.alpha == Material::Alpha::Blend  ? rg::AlphaMode::Blend
                      : m.alpha == Material::Alpha::Mask ? rg::AlphaMode::Mask
                                                         : rg::AlphaMode::Opaque;
        if (!(m.alphaCutoff >= 0.0f && m.alphaCutoff <= 1.0f))
            throw Error("scene material '" + m.name + "': alphaCutoff must be in [0, 1]");
        r.alphaCutoff = m.alphaCutoff;
        r.doubleSided = m.doubleSided;
        const std::pair<const std::string*, std::pair<rg::TextureRef*, bool>> maps[] = {
            {&m.baseColorMap, {&r.baseColorTex, true}},
            {&m.metallicRoughnessMap, {&r.metallicRoughnessTex, false}},
            {&m.normalMap, {&r.normalTex, false}},
            {&m.occlusionMap, {&r.occlusionTex, false}},
            {&m.emissiveMap, {&r.emissiveTex, true}}};
        for (const auto& [file, target] : maps)
            if (!file->empty())
                target.first->image =
                    textureFile(s, "scene material '" + m.name + "'", *file, target.second);
        if (!(m.normalScale >= 0.0f && m.normalScale <= 10.0f))
            throw Error("scene material '" + m.name + "': normalScale must be in [0, 10]");
        r.normalScale = m.normalScale;
        rg::Value::Table params;
        for (const auto& [k, v] : m.params) params[k] = rg::Value(v);
        r.extra = rg::Value(params);
        r.origin = "scene material '" + m.name + "'";
        materials[m.name] = static_cast<uint32_t>(s.materials.size());
        s.materials.push_back(std::move(r));
    }
    for (const Mesh& m : in.meshes) {
        const std::string where = "scene mesh '" + m.name + "'";
        const size_t n = m.positions.size() / 3;
        if (m.positions.size() % 3 || m.normals.size() != m.positions.size() ||
            (!m.uvs.empty() && m.uvs.size() != 2 * n))
            throw Error(where +
                        ": positions and normals need 3 floats per vertex (and uvs 2), the same "
                        "number of vertices");
        if (m.indices.empty() || m.indices.size() % 3)
            throw Error(where + ": indices must be whole triangles");
        for (uint32_t i : m.indices)
            if (i >= n)
                throw Error(where + ": index " + std::to_string(i) + " beyond its " +
                            std::to_string(n) + " vertices");
        auto mat = materials.find(m.material);
        if (mat == materials.end()) throw Error(where + ": unknown material '" + m.material + "'");
        for (const MeshLod& lod : m.lods) {
            if (lod.indices.empty() || lod.indices.size() % 3 || !(lod.error >= 0.0f))
                throw Error(where + ": a level of detail needs whole triangles and an error >= 0");
            for (uint32_t i : lod.indices)
                if (i >= n)
                    throw Error(where + ": level-of-detail index " + std::to_string(i) +
                                " beyond its " + std::to_string(n) + " vertices");
        }
        rg::Primitive p;
        p.material = mat->second;
        p.indices = m.indices;
        for (const MeshLod& lod : m.lods) p.lods.push_back({lod.indices, lod.error});
        p.vertices.resize(n);
        for (size_t v = 0; v < n; ++v) {
            p.vertices[v].position = vec3(&m.positions[3 * v]);
            p.vertices[v].normal = vec3(&m.normals[3 * v]);
            if (!m.uvs.empty()) p.vertices[v].uv0 = {m.uvs[2 * v], m.uvs[2 * v + 1]};
        }
        rg::generateTangents(p);
        rg::Mesh mesh;
        mesh.name = m.name;
        mesh.primitives.push_back(std::move(p));
        s.nodes.push_back(
            {m.name, glm::make_mat4(m.transform), static_cast<int32_t>(s.meshes.size())});
        s.nodes.back().dynamic = m.dynamic;
        s.meshes.push_back(std::move(mesh));
    }
    static const rg::LightType kTypes[] = {rg::LightType::Point,       rg::LightType::Spot,
                                           rg::LightType::Directional, rg::LightType::Sphere,
                                           rg::LightType::Disk,        rg::LightType::Rect,
                                           rg::LightType::Tube};
    for (size_t i = 0; i < in.lights.size(); ++i) {
        const Light& l = in.lights[i];
        // Units, sizes and intensities are checked where every scene's lights become the GPU's
        // (graph/lighting/light_table.cpp convertLights, seed 000 tbl:8).
        rg::Light r;
        r.name = "light" + std::to_string(i);
        r.type = kTypes[static_cast<int>(l.type)];
        r.position = vec3(l.position);
        r.direction = glm::normalize(vec3(l.direction));
        r.color = vec3(l.color);
        r.intensity = l.intensity;
        r.unit = l.unit;
        r.radius = l.radius;
        r.width = l.width;
        r.height = l.height;
        r.length = l.length;
        r.innerAngle = l.innerAngle;
        r.outerAngle = l.outerAngle;
        r.range = l.range;
        r.castShadows = l.shadows;
        const std::string where = "scene light " + std::to_string(i);
        if (l.temperature != 0.0f) {
            const double lo =
                l.daylight ? rg::lights::kMinDaylightTemperature : rg::lights::kMinColorTemperature;
            if (!(l.temperature >= lo && l.temperature <= rg::lights::kMaxColorTemperature))
                throw Error(where + ": temperature " + std::to_string(l.temperature) +
                            " K is outside " + std::to_string(static_cast<int>(lo)) + "-" +
                            std::to_string(static_cast<int>(rg::lights::kMaxColorTemperature)) +
                            " K (" + (l.daylight ? "daylight" : "black body") + ")");
            r.temperatureK = l.temperature;
            r.daylight = l.daylight;
        }
        if (!l.ies.empty()) {
            if (l.type != Light::Type::Point && l.type != Light::Type::Spot)
                throw Error(where + ": an IES profile applies to point and spot lights");
            std::error_code ec;
            r.ies = fs::absolute(l.ies).lexically_normal().string();
            if (!fs::is_regular_file(r.ies, ec))
                throw Error(where + ": cannot open IES profile '" + r.ies + "'");
            if (l.iesMode != "mask" && l.iesMode != "intensity")
                throw Error(where + ": iesMode '" + l.iesMode +
                            "': expected 'mask' or 'intensity'");
            r.iesMode = l.iesMode;
        }
        s.lights.push_back(r);
    }
    for (const Decal& d : in.decals) {
        rg::Decal r;
        r.name = d.name;
        r.world = glm::make_mat4(d.transform);
        r.opacity = d.opacity;
        r.hasBaseColor = d.baseColor[0] >= 0.0f;
        if (r.hasBaseColor) r.baseColor = vec3(d.baseColor);
        r.hasSmoothness = d.smoothness >= 0.0f;
        r.smoothness = r.hasSmoothness ? d.smoothness : r.smoothness;
        r.hasMetalMask = d.metalMask >= 0.0f;
        r.metalMask = r.hasMetalMask ? d.metalMask : r.metalMask;
        r.hasReflectance = d.reflectance >= 0.0f;
        r.reflectance = r.hasReflectance ? d.reflectance : r.reflectance;
        r.normal = d.normal;
        if (!(d.opacity >= 0.0f && d.opacity <= 1.0f))
            throw Error("scene decal '" + d.name + "': opacity must be in [0, 1]");
        s.decals.push_back(r);
    }
    rg::Camera c;
    c.name = "main";
    c.position = vec3(in.camera.position);
    c.target = vec3(in.camera.target);
    c.verticalFov = glm::radians(in.camera.verticalFovDegrees);
    c.aperture = in.camera.aperture;
    c.shutter = in.camera.shutter;
    c.iso = in.camera.iso;
    s.cameras.push_back(c);
    if (in.environment == "sky")
        s.environment = rg::Environment{};
    else if (in.environment != "none" && !in.environment.empty()) {
        rg::Environment e;
        e.kind = "hdr";
        e.file = fs::absolute(in.environment).string();
        s.environment = e;
    }
    rg::buildMeshLods(s);
    rg::computeBounds(s);
    return s;
}

// Lua given as source, written where its errors can point: <cache>/sources/NAME<suffix> (the
// name reduced to letters, digits, '_' and '-'; `fallback` when nothing is left).
std::string writeSource(const std::string& name, const char* fallback, const char* suffix,
                        const std::string& lua) {
    const fs::path dir = fs::path(rg::cacheDir()) / "sources";
    std::error_code ec;
    fs::create_directories(dir, ec);
    std::string safe;
    for (char c : name)
        safe += std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' ? c : '_';
    const fs::path file = dir / ((safe.empty() ? std::string(fallback) : safe) + suffix);
    std::ofstream(file) << lua;
    return file.string();
}

}  // namespace

Mesh makeSphere(float radius, uint32_t segments) {
    return fromPrimitive("sphere", rg::makeSphere(radius, segments, 0));
}
Mesh makePlane(float width, float depth) {
    return fromPrimitive("plane", rg::makePlane(width, depth, 0));
}
Mesh makeBox(float width, float height, float depth) {
    return fromPrimitive("box", rg::makeBox({width, height, depth}, 0));
}

void writePng(const std::string& path, const Image& display) {
    check(rg::writePng(path, fromImage(display)));
}
void writeExr(const std::string& path, const Image& image) {
    static const char* names[] = {"R", "G", "B", "A"};
    std::vector<std::string> channels(names, names + std::min<uint32_t>(image.channels, 4));
    check(rg::writeExr(path, {{"hdr", channels, fromImage(image)}}));
}

struct Renderer::Impl {
    std::unique_ptr<rg::Runtime> runtime;
    std::unique_ptr<rg::Session> session;
    rg::SessionOptions options;
    std::string pipeline;
    // A new session (a new scene, size or captures): the host's parameters and pass switches
    // carry over as its overrides, as far as the pipeline still has and accepts them.
    // Where setTransform put the dynamic meshes: placed again in a new session of the same scene
    // (a new size, a kept resource, another pipeline); a new scene starts without.
    std::map<std::string, glm::mat4> placements;
    void load() {
        if (pipeline.empty()) return;
        auto s = std::make_unique<rg::Session>(*runtime, options);
        if (session) s->carryOverrides(session->overrides());
        check(s->load(pipeline));
        for (const auto& [mesh, world] : placements) check(s->setNodeTransform(mesh, world));
        session = std::move(s);
    }
    // Changes the session's options and loads anew; when the load fails, the options are as they
    // were and the running session goes on (Session::load leaves the runtime to it).
    template <typename Change>
    void reloadWith(Change change) {
        const rg::SessionOptions previous = options;
        change(options);
        if (!session) return;
        try {
            load();
        } catch (...) {
            options = previous;
            throw;
        }
    }
    const rg::Session& loaded() const {
        if (!session) throw Error("no pipeline loaded (loadPipeline first)");
        return *session;
    }
};

Renderer::Renderer(std::unique_ptr<Impl> impl) : m(std::move(impl)) {}
Renderer::~Renderer() = default;

namespace {
std::unique_ptr<rg::Runtime> makeRuntime(const Options& options, const HostDevice* host) {
    if (!options.dataDir.empty()) rg::setProjectRoot(options.dataDir);
    if (!options.cacheDir.empty()) rg::setCacheDir(options.cacheDir);
    rg::RuntimeOptions ro;
    if (options.device >= 0) ro.device = static_cast<uint32_t>(options.device);
    ro.validation = options.validation;
    if (host)
        ro.external = rg::gpu::ExternalDevice{host->instance, host->physicalDevice, host->device,
                                              host->queueFamily, host->queue};
    return check(rg::Runtime::create(ro));
}
}  // namespace

std::unique_ptr<Renderer> Renderer::create(const Options& options) {
    auto impl = std::make_unique<Impl>();
    impl->runtime = makeRuntime(options, nullptr);
    if (options.onceCache) impl->options.onceCache = rg::cacheDir();
    return std::unique_ptr<Renderer>(new Renderer(std::move(impl)));
}

std::unique_ptr<Renderer> Renderer::create(const HostDevice& device, const Options& options) {
    auto impl = std::make_unique<Impl>();
    impl->runtime = makeRuntime(options, &device);
    if (options.onceCache) impl->options.onceCache = rg::cacheDir();
    return std::unique_ptr<Renderer>(new Renderer(std::move(impl)));
}

std::string Renderer::dataDir() { return rg::projectRoot(); }

void Renderer::loadPipeline(const std::string& file) {
    const std::string previous = m->pipeline;
    m->pipeline = fs::absolute(file).string();
    try {
        m->load();
    } catch (...) {
        m->pipeline = previous;  // the previous session keeps running
        throw;
    }
}

void Renderer::loadPipelineSource(const std::string& name, const std::string& lua) {
    loadPipeline(writeSource(name, "pipeline", ".lua", lua));
}

void Renderer::loadScene(const std::string& file) {
    m->placements.clear();
    m->reloadWith([&](rg::SessionOptions& o) {
        o.sceneData.reset();
        o.scene = fs::absolute(file).string();
    });
}

void Renderer::setScene(const Scene& scene) {
    m->placements.clear();
    auto data = std::make_shared<const rg::Scene>(toScene(scene));
    m->reloadWith([&](rg::SessionOptions& o) {
        o.sceneData = data;
        o.scene.clear();
    });
}

void Renderer::loadSceneSource(const std::string& name, const std::string& lua,
                               const std::string& baseDir) {
    const std::string file = writeSource(name, "scene", ".scene.lua", lua);
    std::error_code ec;
    rg::SceneScriptOptions o;
    o.projectRoot = rg::projectRoot();
    o.baseDir = baseDir.empty() ? fs::current_path(ec).string() : baseDir;
    auto data = std::make_shared<const rg::Scene>(check(rg::loadSceneScript(file, o)));
    m->placements.clear();
    m->reloadWith([&](rg::SessionOptions& opts) {
        opts.sceneData = data;
        opts.scene.clear();
    });
}

void Renderer::setSize(uint32_t width, uint32_t height) {
    if (width == 0 || height == 0 || width > 16384 || height > 16384)
        throw Error("setSize: each side must be in 1..16384, got " + std::to_string(width) + "x" +
                    std::to_string(height));
    m->reloadWith([&](rg::SessionOptions& o) {
        o.compile.outputWidth = width;
        o.compile.outputHeight = height;
    });
}

void Renderer::setParameter(const std::string& name, const Value& value) {
    m->loaded();
    check(m->session->setOverride(name,
                                  std::visit([](const auto& x) { return rg::Value(x); }, value)));
}

void Renderer::setPassEnabled(const std::string& pass, bool enabled) {
    m->loaded();
    check(m->session->setPassOverride(pass, enabled));
}

void Renderer::cameraCut() {
    m->loaded();
    m->session->cut();
}

void Renderer::setTransform(const std::string& mesh, const float transform[16]) {
    m->loaded();
    check(m->session->setNodeTransform(mesh, glm::make_mat4(transform)));
    m->placements[mesh] = glm::make_mat4(transform);
}

void Renderer::render(uint32_t frames) {
    m->loaded();
    for (uint32_t f = 0; f < frames; ++f) check(m->session->frame());
    check(m->runtime->executor().finish());
}

Image Renderer::readDisplay() const {
    return toImage(check(m->runtime->executor().readback(m->loaded().pipeline().output)));
}

Image Renderer::readHdr() const {
    const rg::PipelineDesc& p = m->loaded().pipeline();
    if (p.hdr.empty())
        throw Error(
            "readHdr: the pipeline names no HDR output (rg.output { hdr = ..., exposure = ... })");
    return toImage(check(rg::readAbsoluteHdr(m->runtime->executor(), p)).image);
}

void Renderer::record(VkCommandBuffer commandBuffer) {
    if (!commandBuffer) throw Error("record: no command buffer");
    m->loaded();
    check(m->session->frame(commandBuffer));
}

void Renderer::importImage(const std::string& resource, const HostImage& image) {
    m->runtime->executor().setHostImport(resource,
                                         {image.image, image.width, image.height, image.layout});
}

void Renderer::exportImage(const std::string& resource, const HostImage& image) {
    m->runtime->executor().setHostExport(resource,
                                         {image.image, image.width, image.height, image.layout});
}

void Renderer::keep(const std::string& resource) {
    if (std::find(m->options.captures.begin(), m->options.captures.end(), resource) !=
        m->options.captures.end())
        return;
    m->reloadWith([&](rg::SessionOptions& o) { o.captures.push_back(resource); });
}

Image Renderer::readResource(const std::string& name) const {
    m->loaded();
    return toImage(check(m->runtime->executor().readback(name)));
}

std::vector<PassTiming> Renderer::timings() const {
    std::vector<PassTiming> out;
    for (const auto& t : m->runtime->executor().lastTimings()) out.push_back({t.name, t.gpuMs});
    return out;
}

std::string Renderer::planJson() const {
    m->loaded();
    return m->runtime->executor().plan().toJson();
}

}  // namespace rgraph

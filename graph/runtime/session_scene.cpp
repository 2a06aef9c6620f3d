// Session's scene: the scene file (Lua, glTF) or the host's scene read and checked, its materials
// matched to the pipeline's, its lightmap taken from the cache or baked, its camera's exposure.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>

#include "light_shapes.h"
#include "bake/lightmap.h"
#include "core/names.h"
#include "passes/passes.h"
#include "scene/environment.h"
#include "session_detail.h"

namespace fs = std::filesystem;

namespace rg {

using namespace detail;

const Scene* Session::scene() const { return m_scene ? &m_scene->scene() : nullptr; }

namespace detail {

// A value for parameter `name` of `pipeline`, checked against its type and range: what --set,
// the golden tests' params and `rgraph serve`'s controls all go through.
Result<Value> checkedParam(const PipelineDesc& pipeline, const std::string& name,
                           const Value& value) {
    const ParamDesc* p = pipeline.findParam(name);
    if (!p) {
        std::vector<std::string> names;
        for (const auto& d : pipeline.params) names.push_back(d.name);
        return fail(ErrorCode::NotFound, "params." + name + ": the pipeline has no parameter '" +
                                             name + "'" + suggestion(name, names));
    }
    auto checked = checkParamValue(*p, value);
    if (!checked)
        return fail(ErrorCode::InvalidInput, "params." + name + ": " + checked.error().message);
    return *checked;
}

std::string defaultScene() { return projectRoot() + "/scripts/scenes/default.lua"; }

Result<void> applySceneSettings(passes::GpuScene& scene, const PipelineDesc& pipeline) {
    for (const ParamDesc& p : pipeline.params) {
        if (p.sceneSetting.empty()) continue;
        if (auto r = scene.setSetting(p.sceneSetting, p.value); !r)
            return fail(r.error().code, (p.origin.empty() ? "" : p.origin + ": ") + "params." +
                                            p.name + ": scene = '" + p.sceneSetting +
                                            "': " + r.error().message);
    }
    return {};
}

bool hasScenePass(const PipelineDesc& p) {
    return std::any_of(p.graph.passes.begin(), p.graph.passes.end(),
                       [](const PassDesc& d) { return d.kind == "scene"; });
}

ViewFacts viewFactsOf(const Scene& scene) {
    ViewFacts facts;
    for (const Light& l : scene.lights) facts.lights.push_back({l.name, l.castShadows});
    if (scene.bakedLightmap)
        facts.lightmapLobes = static_cast<uint32_t>(scene.bakedLightmap->axes.size());
    return facts;
}

// A scene material's game-team parameters in the order its pipeline material declares them: the
// numeric ones, each the material's value where it gives one, else the declared default.
Value numericParams(const MaterialDesc& pm, const Value& given) {
    Value::Table out;
    for (const auto& [key, def] : pm.params.asTable())
        if (def.isNumber()) out[key] = given[key].isNumber() ? given[key] : def;
    return Value(out);
}

Result<Scene> readScene(const std::string& file, const std::map<std::string, std::string>& args,
                        const std::string& variant) {
    const std::string ext = fs::path(file).extension().string();
    if (!variant.empty() && ext != ".gltf" && ext != ".glb")
        return fail(ErrorCode::InvalidInput,
                    "--variant: applies to a .gltf or .glb scene (a Lua scene gives scene.gltf its "
                    "variant), got '" +
                        file + "'");
    if (ext == ".lua") {
        SceneScriptOptions o;
        o.args = args;
        o.projectRoot = projectRoot();
        return loadSceneScript(file, o);
    }
    if (ext == ".gltf" || ext == ".glb") {
        GltfOptions go;
        go.variant = variant;
        auto scene = loadGltf(file, go);
        if (!scene) return scene;
        if (scene->cameras.empty()) {
            // Frame the bounds from the front, slightly above.
            Camera c;
            c.name = "default";
            const glm::vec3 centre = 0.5f * (scene->boundsMin + scene->boundsMax);
            const float radius =
                std::max(0.5f * glm::length(scene->boundsMax - scene->boundsMin), 0.01f);
            c.target = centre;
            c.position = centre + glm::normalize(glm::vec3(0.0f, 0.35f, 1.0f)) * radius /
                                      std::sin(c.verticalFov * 0.5f);
            c.nearPlane = radius * 0.01f;
            c.farPlane = radius * 100.0f;
            scene->cameras.push_back(c);
        }
        return scene;
    }
    return fail(ErrorCode::InvalidInput,
                "--scene '" + file + "': expected a .lua scene script, a .gltf or a .glb file");
}

}  // namespace detail

// Loads the scene the pipeline's scene passes draw, matches its materials to the pipeline's, and
// takes the camera's exposure settings into the camera parameters.
Result<std::unique_ptr<passes::GpuScene>> Session::loadScene(PipelineDesc& pipeline) {
    // A scene built in code (the library's setScene) or read from its file.
    const std::string file = m_options.sceneData       ? std::string("the host's scene")
                             : m_options.scene.empty() ? defaultScene()
                                                       : m_options.scene;
    auto scene = m_options.sceneData ? Result<Scene>(*m_options.sceneData)
                                     : readScene(file, m_options.sceneArgs, m_options.variant);
    if (!scene) return std::unexpected(scene.error());
    for (const auto& w : scene->warnings) warn("warning: " + w);
    if (const Scene::LodStats& l = scene->lodStats; l.primitives > 0) {
        char line[160];
        std::snprintf(line, sizeof line,
                      "levels of detail: %zu meshes, %zu levels (%zu meshes' from the cache), "
                      "%.1f ms",
                      l.primitives, l.levels, l.cached, l.ms);
        note(line);
    }
    const std::string ext =
        m_options.sceneData ? std::string() : fs::path(file).extension().string();
    if (auto r = chooseEnvironment(*scene, m_options.environment,
                                   /*litByDefault=*/ext == ".gltf" || ext == ".glb");
        !r)
        return std::unexpected(r.error());
    if (const std::string& mode = m_options.environmentSun; !mode.empty()) {
        if (std::find(kEnvironmentSunModes.begin(), kEnvironmentSunModes.end(), mode) ==
            kEnvironmentSunModes.end())
            return fail(
                ErrorCode::InvalidInput,
                "--environment-sun: expected auto, light, remove or keep, got '" + mode + "'");
        if (scene->environment) scene->environment->sun = mode;
    }
    if (auto sun = takeEnvironmentSun(*scene); !sun)
        return std::unexpected(sun.error());
    else if (!sun->empty())
        note(*sun);
    for (Material& m : scene->materials) {
        auto pm = std::find_if(pipeline.materials.begin(), pipeline.materials.end(),
                               [&](auto& x) { return x.name == m.model; });
        if (pm == pipeline.materials.end()) {
            std::string names;
            for (const auto& x : pipeline.materials)
                names += (names.empty() ? "'" : ", '") + x.name + "'";
            return fail(ErrorCode::InvalidInput,
                        file + ": material '" + m.name + "' uses model '" + m.model +
                            "', which the pipeline does not declare (materials: " + names + ")");
        }
        // Game-team parameters by name, in the order the shaders read them (the pipeline
        // material's), each checked: a key the model does not have, or a value of another type,
        // is an error naming where the scene declared it.
        const std::string where =
            (m.origin.empty() ? file + ": material '" + m.name + "'" : m.origin) + ".params.";
        std::vector<std::string> known;
        for (const auto& [key, def] : pm->params.asTable()) known.push_back(key);
        for (const auto& [key, value] : m.extra.asTable()) {
            const Value& def = pm->params[key];
            if (def.isNil())
                return fail(ErrorCode::InvalidInput,
                            where + key + ": model '" + m.model + "' has no parameter '" + key +
                                "'" + suggestion(key, known) +
                                (known.empty() ? " (it takes none)"
                                               : "; its parameters: " + joinQuoted(known)));
            if (def.isNumber() && !value.isNumber())
                return fail(ErrorCode::InvalidInput,
                            where + key + ": expected a number (as model '" + m.model +
                                "' declares it), got " + value.typeName());
        }
        m.extra = numericParams(*pm, m.extra);
        // Its own textures by name: one the model does not declare is an error; the ones it
        // declares and the scene leaves out are white, so the map's order is the slots'.
        const std::string at =
            (m.origin.empty() ? file + ": material '" + m.name + "'" : m.origin) + ".textures.";
        for (const auto& [key, ref] : m.textures)
            if (std::find(pm->textures.begin(), pm->textures.end(), key) == pm->textures.end())
                return fail(
                    ErrorCode::InvalidInput,
                    at + key + ": model '" + m.model + "' has no texture '" + key + "'" +
                        suggestion(key, pm->textures) +
                        (pm->textures.empty() ? " (it takes none)"
                                              : "; its textures: " + joinQuoted(pm->textures)));
        for (const auto& name : pm->textures) m.textures[name];
    }
    // A boolean parameter read when the scene loads: the pipeline's value, or --set's (checked).
    auto switchedOn = [&](const char* name) -> Result<bool> {
        const ParamDesc* use = pipeline.findParam(name);
        Value on = use ? use->value : Value(true);
        if (auto set = m_options.params.find(name); use && set != m_options.params.end()) {
            auto checked = checkedParam(pipeline, name, set->second);
            if (!checked) return std::unexpected(checked.error());
            on = *checked;
        }
        return !on.isBool() || on.asBool();
    };
    // Baked GI (scene.lightmap): from the cache, or baked now; the pipeline's `lightmap` parameter
    // (scripts/lightmap.lua) turns it off.
    if (scene->lightmap) {
        auto on = switchedOn("lightmap");
        if (!on) return std::unexpected(on.error());
        if (*on) {
            bake::PrepareOptions po;
            po.cacheDir = cacheDir() + "/lightmaps";
            po.bake = m_options.bakeLightmap;
            if (auto r = bake::prepareLightmap(*scene, po); !r)
                return fail(r.error().code, scene->lightmap->origin + ": scene.lightmap." +
                                                scene->lightmap->name + ": " + r.error().message);
        }
    }
    // The area lights' emissive shapes (seed 002 §4.8), after the bake: the lightmap neither
    // charts nor sees them. The `light_shapes` parameter (scripts/lighting.lua) turns them off; a
    // pipeline without the standard material draws none.
    auto shapesOn = switchedOn("light_shapes");
    if (!shapesOn) return std::unexpected(shapesOn.error());
    if (auto standard = std::find_if(pipeline.materials.begin(), pipeline.materials.end(),
                                     [](auto& x) { return x.name == "standard"; });
        *shapesOn && standard != pipeline.materials.end()) {
        auto shapes = addLightShapes(*scene, numericParams(*standard, Value()));
        if (!shapes) return std::unexpected(shapes.error());
    }
    passes::GpuSceneOptions sceneOptions;
    sceneOptions.levelsOfDetail = m_options.levelsOfDetail;
    auto gpuScene = passes::GpuScene::create(m_runtime.gpu(), std::move(*scene), sceneOptions);
    if (!gpuScene) return std::unexpected(gpuScene.error());
    if (!m_options.camera.empty())
        if (auto r = (*gpuScene)->selectCamera(m_options.camera); !r)
            return std::unexpected(r.error());
    const Camera& cam = (*gpuScene)->camera();
    auto set = [&](const char* name, double v) {
        if (ParamDesc* p = pipeline.findParam(name))
            if (auto ok = checkParamValue(*p, Value(v))) p->value = *ok;
    };
    set("aperture", cam.aperture);
    set("shutter", cam.shutter);
    set("iso", cam.iso);
    set("ec", cam.exposureCompensation);
    set("initial_ev100", std::log2(cam.aperture * cam.aperture / cam.shutter * 100.0 / cam.iso) -
                             cam.exposureCompensation);
    m_sceneFile = file;
    return std::move(*gpuScene);
}

}  // namespace rg

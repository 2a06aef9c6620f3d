// `rgraph bake`: a scene's SG lightmap, baked with Embree (or found in the cache).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "bake/lightmap.h"
#include "scene/environment.h"
#include "scene/scene.h"
#include "cli.h"

namespace rg::cli {

namespace {

const char* const kHelp =
    "usage: rgraph bake [--scene FILE.lua] [--scene-arg NAME=VALUE]... [--out FILE.exr] "
    "[--rebake]\n\n"
    "Bakes the scene's spherical-Gaussian lightmap (its scene.lightmap declaration; seed 003) on "
    "the CPU:\n"
    "paths traced with Intel Embree from every texel of the scene's lightmap atlas, the incoming\n"
    "radiance fitted to N non-negative SG lobes. The result is cached by the scene's content hash "
    "in\n"
    "the cache folder (RG_CACHE_DIR)/lightmaps, where `rgraph render` finds it; a scene or setting "
    "that\n"
    "changes bakes anew. --rebake bakes even when the cache has it; --out also writes the "
    "lightmap\n"
    "EXR there (a layer per lobe: sg0.R ... with the basis in its header).\n";

}  // namespace

int cmdBake(int argc, char** argv) {
    Args args;
    if (auto done =
            parseCommand(argc, argv, "bake", {"scene", "scene-arg", "out", "rebake"}, kHelp, args))
        return *done;
    const std::string file = args.get("scene", projectRoot() + "/scripts/scenes/default.lua");
    const std::string ext = fs::path(file).extension().string();
    std::map<std::string, std::string> sceneArgs;
    for (const auto& a : args.all("scene-arg")) {
        const auto eq = a.find('=');
        if (eq == std::string::npos || eq == 0)
            return usageError("--scene-arg must be NAME=VALUE, got '" + a + "'", "bake");
        sceneArgs[a.substr(0, eq)] = a.substr(eq + 1);
    }
    SceneScriptOptions so;
    so.args = sceneArgs;
    so.projectRoot = projectRoot();
    auto scene = ext == ".lua" ? loadSceneScript(file, so) : loadGltf(file);
    if (!scene) return report(scene.error());
    if (!scene->lightmap)
        return report(
            Error(ErrorCode::InvalidInput, file + ": the scene declares no scene.lightmap (e.g. "
                                                  "scene.lightmap \"gi\" { density = 4 })"));
    if (auto r = chooseEnvironment(*scene, "", ext == ".gltf" || ext == ".glb"); !r)
        return report(r.error());
    if (auto sun = takeEnvironmentSun(*scene); !sun) return report(sun.error());
    bake::PrepareOptions po;
    po.cacheDir = cacheDir() + "/lightmaps";
    po.rebake = args.has("rebake");
    po.bake = bake::bakeLightmap;
    bake::BakeStats stats;
    bool fromCache = false;
    std::string path;
    po.stats = &stats;
    po.fromCache = &fromCache;
    po.path = &path;
    if (auto r = bake::prepareLightmap(*scene, po); !r)
        return report(Error(r.error().code, scene->lightmap->origin + ": scene.lightmap." +
                                                scene->lightmap->name + ": " + r.error().message));
    const Lightmap& lm = *scene->bakedLightmap;
    const double mib = double(lm.width) * lm.height * double(lm.axes.size()) * 3 * 4 / (1 << 20);
    const double gpuMib = double(lm.width) * lm.height * double(lm.axes.size() + 1) * 8 /
                          (1 << 20);  // + the flat normal's irradiance
    std::printf(
        "rgraph: lightmap %ux%u, %zu lobes (sharpness %.3f), %.2f texels/m: %.2f MiB as 32-bit "
        "floats, %.2f MiB on the GPU (RGBA16F)\n",
        lm.width, lm.height, lm.axes.size(), double(lm.sharpness), double(lm.density), mib, gpuMib);
    if (fromCache)
        std::printf("rgraph: up to date in the cache: %s\n", path.c_str());
    else
        std::printf(
            "rgraph: baked %u texels in %.2f s: %.1f M rays (Embree), %.2f M rays/s; cached as "
            "%s\n",
            stats.texels, stats.seconds, double(stats.rays) * 1e-6,
            stats.seconds > 0 ? double(stats.rays) / stats.seconds * 1e-6 : 0.0, path.c_str());
    if (args.has("out")) {
        if (auto r = bake::writeLightmapExr(args.get("out"), lm); !r) return report(r.error());
        std::printf("rgraph: wrote %s\n", args.get("out").c_str());
    }
    return kOk;
}

}  // namespace rg::cli

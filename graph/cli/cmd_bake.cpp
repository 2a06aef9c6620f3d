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
    "[--rebake] [--shard K/N] [--threads N]\n"
    "       rgraph bake --merge PART.exr... [--out FILE.exr]\n\n"
    "Bakes the scene's spherical-Gaussian lightmap (its scene.lightmap declaration; seed 003) on "
    "the CPU:\n"
    "paths traced with Intel Embree from every texel of the scene's lightmap atlas, the incoming\n"
    "radiance fitted to N non-negative SG lobes. The result is cached by the scene's content hash "
    "in\n"
    "the cache folder (RG_CACHE_DIR)/lightmaps, where `rgraph render` finds it; a scene or setting "
    "that\n"
    "changes bakes anew. --rebake bakes even when the cache has it; --out also writes the "
    "lightmap\n"
    "EXR there (a layer per lobe: sg0.R ... with the basis in its header).\n"
    "--shard K/N bakes shard K of N (1 <= K <= N): the atlas's covered texels in row order, dealt "
    "out in\n"
    "runs of 256, run r to shard r mod N; the part is cached as KEY.shard-K-of-N.exr (a rerun "
    "finds "
    "it)\n"
    "and written to --out. --merge joins the N parts of one bake into the whole lightmap, "
    "bit-identical\n"
    "to baking it in one go, caches it where `rgraph render` finds it and writes --out; parts of "
    "another\n"
    "scene or settings, a shard given twice or missing are refused (tools/farm.py runs the shards "
    "on a\n"
    "cluster).\n"
    "--threads N bakes on N threads (default: one per core).\n";

int mergeParts(const Args& args) {
    std::vector<std::string> parts = args.all("merge");
    for (const auto& p : args.all("")) parts.push_back(p);
    auto merged = bake::mergeLightmapParts(parts);
    if (!merged) return report(merged.error());
    const std::string dir = cacheDir() + "/lightmaps", path = dir + "/" + merged->key + ".exr";
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (auto r = bake::writeLightmapExr(path, *merged); !r) return report(r.error());
    const size_t covered =
        size_t(std::count(merged->coverage.begin(), merged->coverage.end(), uint8_t(1)));
    std::printf(
        "rgraph: merged %zu parts: lightmap %ux%u, %zu lobes, %zu covered texels; cached "
        "as %s\n",
        parts.size(), merged->width, merged->height, merged->axes.size(), covered, path.c_str());
    if (args.has("out")) {
        if (auto r = bake::writeLightmapExr(args.get("out"), *merged); !r) return report(r.error());
        std::printf("rgraph: wrote %s\n", args.get("out").c_str());
    }
    return kOk;
}

template <typename Failed>
int bakeShard(const Args& args, Scene& scene, bake::PrepareOptions& po, uint32_t shard,
              uint32_t shards, Failed failed) {
    auto part = bake::prepareLightmapShard(scene, po, shard, shards);
    if (!part) return failed(part.error());
    const auto& p = part->part;
    if (*po.fromCache)
        std::printf("rgraph: shard %u/%u (%u of %u covered texels) up to date in the cache: %s\n",
                    shard + 1, shards, p.texels, p.covered, po.path->c_str());
    else
        std::printf(
            "rgraph: baked shard %u/%u: %u of %u covered texels in %.2f s: %.1f M rays, %.2f M "
            "rays/s; cached as %s\n",
            shard + 1, shards, p.texels, p.covered, po.stats->seconds,
            double(po.stats->rays) * 1e-6,
            po.stats->seconds > 0 ? double(po.stats->rays) / po.stats->seconds * 1e-6 : 0.0,
            po.path->c_str());
    if (args.has("out")) {
        if (auto r = bake::writeLightmapExr(args.get("out"), part->lightmap, &p); !r)
            return report(r.error());
        std::printf("rgraph: wrote %s\n", args.get("out").c_str());
    }
    return kOk;
}

}  // namespace

int cmdBake(int argc, char** argv) {
    Args args;
    if (auto done = parseCommand(
            argc, argv, "bake",
            {"scene", "scene-arg", "out", "rebake", "shard", "merge", "threads"}, kHelp, args))
        return *done;
    if (args.has("merge")) {
        for (const char* o : {"shard", "scene", "scene-arg", "rebake"})
            if (args.has(o))
                return usageError(std::string("--merge takes parts, not --") + o, "bake");
        return mergeParts(args);
    }
    if (!args.all("").empty())
        return usageError(
            "unexpected argument '" + args.all("").front() + "' (only --merge takes files)",
            "bake");
    uint32_t shard = 0, shards = 1;
    if (args.has("shard") && !parseShard(args.get("shard"), shard, shards))
        return usageError("--shard must be K/N with 1 <= K <= N, got '" + args.get("shard") + "'",
                          "bake");
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
    if (args.has("threads") && !parseCount(args.get("threads"), po.threads))
        return usageError(
            "--threads must be a positive whole number, got '" + args.get("threads") + "'", "bake");
    po.bake = bake::bakeLightmap;
    bake::BakeStats stats;
    bool fromCache = false;
    std::string path;
    po.stats = &stats;
    po.fromCache = &fromCache;
    po.path = &path;
    auto failed = [&](const Error& e) {
        return report(Error(e.code, scene->lightmap->origin + ": scene.lightmap." +
                                        scene->lightmap->name + ": " + e.message));
    };
    if (args.has("shard")) return bakeShard(args, *scene, po, shard, shards, failed);
    if (auto r = bake::prepareLightmap(*scene, po); !r) return failed(r.error());
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

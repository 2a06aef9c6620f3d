// `rgraph export-scene`: a Lua scene written as binary glTF.
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

#include "scene/environment.h"
#include "scene/scene.h"
#include "cli.h"

namespace rg::cli {

namespace {

const char* const kHelp =
    "usage: rgraph export-scene --scene SCENE.lua --out FILE.glb\n\n"
    "Builds a Lua scene (or reads a .gltf/.glb) and writes it as binary glTF: meshes, materials\n"
    "(metallic-roughness; what glTF cannot say goes to the material's extras), embedded images,\n"
    "cameras and the lights glTF can express (KHR_lights_punctual: cd, lux).\n";

}  // namespace

int cmdExportScene(int argc, char** argv) {
    Args args;
    if (auto done = parseCommand(argc, argv, "export-scene", {"scene", "out"}, kHelp, args))
        return *done;
    std::vector<std::string> positional = args.all("");
    std::string scene = args.get("scene", positional.size() > 0 ? positional[0] : "");
    std::string out = args.get("out", positional.size() > 1 ? positional[1] : "");
    if (scene.empty() || out.empty())
        return usageError("give --scene SCENE and --out FILE.glb", "export-scene");
    const std::string ext = fs::path(scene).extension().string();
    auto loaded = ext == ".lua" ? loadSceneScript(scene) : loadGltf(scene);
    if (!loaded) return report(loaded.error());
    std::vector<std::string> warnings;
    if (auto r = exportGlb(*loaded, out, &warnings); !r) return report(r.error());
    for (const auto& w : warnings) std::fprintf(stderr, "rgraph: warning: %s\n", w.c_str());
    std::printf("rgraph: wrote %s (%zu meshes, %zu materials, %zu lights, %zu cameras)\n",
                out.c_str(), loaded->meshes.size(), loaded->materials.size(), loaded->lights.size(),
                loaded->cameras.size());
    return kOk;
}

}  // namespace rg::cli

// rgraph: the command line. Exit codes: 0 success, 1 a failed check or a device failure,
// 2 bad usage or bad input. Each command is a file of its own (cmd_*.cpp); `test` is the golden
// runner's (graph/golden/command.cpp).
#include <cstdio>
#include <cstring>
#include <string>

#include "cli.h"
#include "golden/command.h"

using namespace rg::cli;

namespace {

const char* kMainHelp =
    "usage: rgraph COMMAND [OPTIONS]\n"
    "\n"
    "A data-driven render graph on Vulkan (headless; lavapipe when there is no GPU).\n"
    "\n"
    "commands:\n"
    "  devices   list Vulkan devices and mark the one rgraph would choose\n"
    "  render    render a pipeline to EXR (linear) and PNG (display)\n"
    "  graph     print the compiled plan of a pipeline as DOT or JSON\n"
    "  bench     time every pass over several frames\n"
    "  watch     re-render whenever a script or shader of the pipeline changes\n"
    "  serve     render continuously and serve a live page: graph, timings, controls, any image\n"
    "  export-scene  write a Lua scene as binary glTF (.glb)\n"
    "  bake      bake a scene's SG lightmap (scene.lightmap) with Embree: progress, time, rays/s\n"
    "  accuracy  area lights, real-time against the reference mode: error table and heat-map page\n"
    "  test      run the golden-image tests (tests/golden/*.lua): --update, --report DIR, --junit "
    "FILE\n"
    "  compare   error between two EXR renders: relative error, RMSE, PSNR, heat map\n"
    "  gallery   every glTF in a folder rendered into one page: image, status, warnings\n"
    "\n"
    "'rgraph COMMAND --help' describes each command. Exit codes: 0 success, 1 failed check or\n"
    "device failure, 2 bad usage or bad input.\n"
    "Environment: RG_VALIDATION=1 turns on the Vulkan validation layer; RG_CACHE_DIR moves the\n"
    "shader caches; RG_ROOT points at the project folder (shaders/, scripts/).\n";

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2 || !std::strcmp(argv[1], "--help") || !std::strcmp(argv[1], "-h") ||
        !std::strcmp(argv[1], "help")) {
        std::printf("%s", kMainHelp);
        return argc < 2 ? kUsage : kOk;
    }
    std::string cmd = argv[1];
    if (cmd == "devices") return cmdDevices(argc, argv);
    if (cmd == "render") return cmdRender(argc, argv);
    if (cmd == "graph") return cmdGraph(argc, argv);
    if (cmd == "bench") return cmdBench(argc, argv);
    if (cmd == "watch") return cmdWatch(argc, argv);
    if (cmd == "serve") return cmdServe(argc, argv);
    if (cmd == "export-scene") return cmdExportScene(argc, argv);
    if (cmd == "bake") return cmdBake(argc, argv);
    if (cmd == "accuracy") return cmdAccuracy(argc, argv);
    if (cmd == "test") return rg::goldenCommand(argc, argv);
    if (cmd == "compare") return cmdCompare(argc, argv);
    if (cmd == "gallery") return cmdGallery(argc, argv);
    std::fprintf(stderr, "rgraph: unknown command '%s'\n\n%s", cmd.c_str(), kMainHelp);
    return kUsage;
}

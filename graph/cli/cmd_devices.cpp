// `rgraph devices`: the Vulkan devices and the one rgraph would choose.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "cli.h"
#include "golden/golden_set.h"

namespace rg::cli {

namespace {

const char* const kHelp =
    "usage: rgraph devices [--family]\n\nLists the Vulkan devices; '*' marks the one rgraph "
    "chooses\n"
    "(discrete GPU, then integrated, then CPU). Use --device N with other commands to override.\n"
    "Each device's family is what its golden images are kept under (tests/golden/README.md): the "
    "first\n"
    "word of its driver's name, or RG_DEVICE_FAMILY when set. --family prints only the chosen "
    "device's.\n";

}  // namespace

int cmdDevices(int argc, char** argv) {
    Args args;
    if (auto done = parseCommand(argc, argv, "devices", {"family"}, kHelp, args)) return *done;
    prepareEnvironment();
    auto devices = gpu::Context::listDevices();
    if (!devices) return report(devices.error());
    int chosen = -1, bestRank = 99;
    auto rank = [](const std::string& t) {
        return t == "discrete"     ? 0
               : t == "integrated" ? 1
               : t == "virtual"    ? 2
               : t == "cpu"        ? 3
                                   : 4;
    };
    for (const auto& d : *devices)
        if (d.usable && rank(d.type) < bestRank)
            bestRank = rank(d.type), chosen = static_cast<int>(d.index);
    const char* familyOverride = std::getenv("RG_DEVICE_FAMILY");
    auto family = [&](const gpu::DeviceInfo& d) {
        return golden::deviceFamily(familyOverride && *familyOverride ? familyOverride : d.driver);
    };
    if (args.has("family")) {
        for (const auto& d : *devices)
            if (static_cast<int>(d.index) == chosen) std::printf("%s\n", family(d).c_str());
        return chosen < 0 ? kFailed : kOk;
    }
    for (const auto& d : *devices) {
        std::printf("%c %u  %-40s %-10s Vulkan %u.%u.%u  %s  (family %s)%s%s\n",
                    static_cast<int>(d.index) == chosen ? '*' : ' ', d.index, d.name.c_str(),
                    d.type.c_str(), VK_API_VERSION_MAJOR(d.apiVersion),
                    VK_API_VERSION_MINOR(d.apiVersion), VK_API_VERSION_PATCH(d.apiVersion),
                    d.driver.c_str(), family(d).c_str(),
                    d.usable ? "" : "  (unusable: ", d.usable ? "" : (d.whyNot + ")").c_str());
    }
    if (devices->empty()) {
        std::fprintf(stderr,
                     "rgraph: no Vulkan devices (install mesa-vulkan-drivers for lavapipe)\n");
        return kFailed;
    }
    return kOk;
}

}  // namespace rg::cli

// `rgraph accuracy`: area lights in real time against the reference mode; with --ibl the distant
// probe's filtering against its definitions.
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

#include <unistd.h>

#include "accuracy.h"
#include "accuracy_ibl.h"
#include "cli.h"

namespace fs = std::filesystem;

namespace rg::cli {

namespace {

const char* const kHelp =
    "usage: rgraph accuracy [--size WxH] [--frames N] [--samples S] [--light L]... [--placement "
    "P]... [--material M]... [--model M]...\n"
    "                       [--report DIR]\n\n"
    "Renders every area light type (sphere, disk, rect, tube) x placement (facing, grazing, "
    "horizon: crossing\n"
    "the floor's plane) x material (rough, glossy dielectric, glossy metal) of "
    "scripts/scenes/accuracy.lua\n"
    "with the real-time pipeline under each area-light model (frostbite, ltc: the pipeline's "
    "area_lights)\n"
    "and with the reference mode (reference.lua, N frames of S samples (default 4), in\n"
    "two independent halves), and prints per case the mean and 95th-percentile relative error and "
    "the\n"
    "energy error over the pixels the reference lights above 1 % of its peak, beside the "
    "reference's\n"
    "own noise (the halves' mean relative difference / 2). --report DIR writes DIR/index.html with "
    "a\n"
    "heat map per case (default out/accuracy). Defaults: 160x120, 64 frames per half, every "
    "case.\n\n"
    "usage: rgraph accuracy --ibl [--environment FILE|sky|synthetic]... [--directions N] "
    "[--report DIR]\n\n"
    "The distant light probe (scripts/ibl.lua) against integrals over every texel of the cube its "
    "filters read:\n"
    "the order-2 SH irradiance against the exact irradiance, each pre-filtered mip against the "
    "split sum's\n"
    "definition (v = n) in N x N directions of each face (default 4), the DFG table against the "
    "BRDF's\n"
    "integrators. Environments: .hdr/.exr files, the sky, or a synthetic 0.5 deg sun of 40 000 "
    "nits over\n"
    "10 nits (default: synthetic and sky); the sun stays in the probe (--environment-sun keep), "
    "the hard case.\n"
    "Exits 1 when a bound is broken: a pre-filtered mip's worst 5 % (its mean 2 % where the lobe "
    "is under\n"
    "two source texels), the SH 10 % where the irradiance is at least a quarter of its peak, the "
    "DFG 0.01.\n";

}  // namespace

namespace {

int iblAccuracy(const Args& args) {
    IblAccuracyOptions o;
    if (!args.all("environment").empty()) o.environments = args.all("environment");
    if (args.has("directions") &&
        (!parseCount(args.get("directions"), o.directionsPerFace) || o.directionsPerFace > 64))
        return usageError("--directions must be a whole number from 1 to 64", "accuracy");
    for (const std::string& e : o.environments)
        if (e != "sky" && e != "synthetic" && !fs::exists(e))
            return usageError("--environment '" + e + "': no such file (or sky, synthetic)",
                              "accuracy");
    auto rt = Runtime::create({});
    if (!rt) return report(rt.error());
    o.progress = [](const std::string& name, size_t i, size_t n) {
        std::fprintf(stderr, "rgraph: accuracy --ibl %zu/%zu: %s\n", i + 1, n, name.c_str());
    };
    auto result = runIblAccuracy(**rt, o);
    if (!result) return report(result.error());
    std::printf("%s", iblAccuracyTable(*result).c_str());
    const std::string dir = args.get("report", "out/accuracy_ibl");
    if (auto r = writeIblAccuracyReport(*result, dir); !r) return report(r.error());
    std::printf("rgraph: wrote %s/index.html\n", dir.c_str());
    if ((*rt)->gpu().validationMessageCount()) return kFailed;
    return result->pass() ? kOk : kFailed;
}

}  // namespace

int cmdAccuracy(int argc, char** argv) {
    Args args;
    if (auto done = parseCommand(argc, argv, "accuracy",
                                 {"size", "frames", "samples", "light", "placement", "material",
                                  "model", "report", "ibl", "environment", "directions"},
                                 kHelp, args))
        return *done;
    if (args.has("ibl")) return iblAccuracy(args);
    AccuracyOptions o;
    if (args.has("size") && !parseSize(args.get("size"), o.width, o.height))
        return usageError(
            "--size must be WIDTHxHEIGHT, e.g. 160x120; got '" + args.get("size") + "'",
            "accuracy");
    if (args.has("frames") && !parseCount(args.get("frames"), o.frames))
        return usageError("--frames must be a positive whole number", "accuracy");
    if (args.has("samples") && (!parseCount(args.get("samples"), o.samples) || o.samples > 1024))
        return usageError("--samples must be a whole number from 1 to 1024", "accuracy");
    auto pick = [&](const char* option, std::vector<std::string>& list) -> bool {
        const auto chosen = args.all(option);
        if (chosen.empty()) return true;
        for (const auto& c : chosen)
            if (std::find(list.begin(), list.end(), c) == list.end()) {
                std::string all;
                for (const auto& x : list) all += (all.empty() ? "'" : ", '") + x + "'";
                usageError("--" + std::string(option) + " '" + c + "': expected one of " + all,
                           "accuracy");
                return false;
            }
        list = chosen;
        return true;
    };
    if (!pick("light", o.lights) || !pick("placement", o.placements) ||
        !pick("material", o.materials) || !pick("model", o.models))
        return kUsage;
    auto rt = Runtime::create({});
    if (!rt) return report(rt.error());
    const bool tty = isatty(fileno(stderr));
    o.progress = [tty](const std::string& name, size_t i, size_t n) {
        std::fprintf(stderr,
                     tty ? "\rrgraph: accuracy %zu/%zu: %-28s" : "rgraph: accuracy %zu/%zu: %s\n",
                     i + 1, n, name.c_str());
    };
    auto cases = runAccuracy(**rt, o);
    if (tty) std::fprintf(stderr, "\n");
    if (!cases) return report(cases.error());
    std::printf("%s", accuracyTable(*cases).c_str());
    const std::string dir = args.get("report", "out/accuracy");
    if (auto r = writeAccuracyReport(*cases, dir); !r) return report(r.error());
    std::printf("rgraph: wrote %s/index.html (%ux%u, %u reference frames per half)\n", dir.c_str(),
                o.width, o.height, o.frames);
    return (*rt)->gpu().validationMessageCount() ? kFailed : kOk;
}

}  // namespace rg::cli

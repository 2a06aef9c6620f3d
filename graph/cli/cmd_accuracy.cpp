// `rgraph accuracy`: area lights in real time against the reference mode.
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
#include "cli.h"

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
    "case.\n";

}  // namespace

int cmdAccuracy(int argc, char** argv) {
    Args args;
    if (auto done = parseCommand(
            argc, argv, "accuracy",
            {"size", "frames", "samples", "light", "placement", "material", "model", "report"},
            kHelp, args))
        return *done;
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

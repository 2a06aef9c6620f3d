// `rgraph watch`: re-renders whenever a script, shader or scene of the pipeline changes.
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

#include "file_watch.h"
#include <future>
#include <thread>
#include <unistd.h>
#include "cli.h"

namespace rg::cli {

namespace {

const char* const kHelp =
    "usage: rgraph watch [--pipeline FILE.lua] [--scene FILE] [--size WxH] [--out FILE.exr] [--png "
    "FILE.png]\n"
    "                    [--scene-arg NAME=VALUE]... [--set NAME=VALUE]... [--environment "
    "FILE|sky|none] [--interval MS] [--max-reloads N]\n\n" RG_HELP_ENVIRONMENT
    "Renders once, then re-renders whenever a script or shader the pipeline uses changes (polled\n"
    "every MS milliseconds, default 250). A script that fails to load or compile is reported and "
    "the\n"
    "previous pipeline keeps running. Stops after N reloads when --max-reloads is given.\n";

}  // namespace

int cmdWatch(int argc, char** argv) {
    Args args;
    if (auto done = parseCommand(
            argc, argv, "watch",
            {"pipeline", "scene", "scene-arg", "set", "camera", "environment", "environment-sun",
             "variant", "size", "out", "png", "device", "interval", "max-reloads", "no-cache"},
            kHelp, args))
        return *done;
    uint32_t interval = 250, maxReloads = 0;
    if (args.has("interval") && !parseCount(args.get("interval"), interval))
        return usageError("--interval must be milliseconds", "watch");
    if (args.has("max-reloads") && !parseCount(args.get("max-reloads"), maxReloads))
        return usageError("--max-reloads must be a count", "watch");
    if (isBuiltin(pipelineArg(args))) return usageError("watch needs a pipeline script", "watch");
    auto paths = outputPaths(args, "out/watch.exr");
    if (!paths) return report(paths.error());
    auto setup = setupRun(args, "watch", 1, {}, /*verbose=*/true);
    if (!setup) return report(setup.error());
    Session& session = *setup->session;
    const auto [exrPath, pngPath] = *paths;
    auto renderOnce = [&]() -> Result<void> {
        if (auto r = session.frame(); !r) return r;
        auto written = writeOutputs(*setup, exrPath, pngPath, {});
        if (!written) return std::unexpected(written.error());
        return {};
    };
    if (auto r = renderOnce(); !r) return report(r.error());
    std::printf("rgraph watch: rendered %s; watching %zu files\n", pngPath.c_str(),
                session.files().size());
    std::fflush(stdout);
    FileWatch watched;
    watched.changed(session.files());
    for (uint32_t reloads = 0; maxReloads == 0 || reloads < maxReloads;) {
        std::this_thread::sleep_for(std::chrono::milliseconds(interval));
        if (!watched.changed(session.files())) continue;
        ++reloads;
        if (auto r = session.load(setup->pipeline); !r) {
            std::printf("rgraph watch: reload failed, the previous pipeline keeps running:\n%s\n",
                        r.error().describe().c_str());
            std::fflush(stdout);
            continue;
        }
        if (auto r = renderOnce(); !r) {
            std::printf("rgraph watch: render failed: %s\n", r.error().describe().c_str());
            std::fflush(stdout);
            continue;
        }
        std::printf("rgraph watch: reloaded and rendered %s\n", pngPath.c_str());
        std::fflush(stdout);
    }
    return kOk;
}

}  // namespace rg::cli

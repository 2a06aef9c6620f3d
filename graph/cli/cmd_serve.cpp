// `rgraph serve`: its options; the server itself is serve.cpp.
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

#include "serve.h"
#include "cli.h"

namespace rg::cli {

namespace {

const char* const kHelp =
    "usage: rgraph serve [--pipeline FILE.lua] [--scene FILE] [--size WxH] [--port N] [--host "
    "ADDRESS] [--token TOKEN] [--interval MS]\n"
    "                    [--scene-arg NAME=VALUE]... [--set NAME=VALUE]... [--environment "
    "FILE|sky|none]\n\n"
    "Renders the pipeline continuously (headless) and serves a page at http://HOST:PORT/ (default\n"
    "127.0.0.1:8080; --port 0 takes a free port; the address is printed) showing the compiled "
    "graph,\n"
    "per-pass GPU times, every parameter and pass switch as a control, any texture or G-buffer\n"
    "channel as an image with an exposure slider (EXR download), and script errors with file:line\n"
    "while the last good plan keeps rendering; scripts are reloaded when they change, as `watch`\n"
    "does. The page uses only the JSON API beneath it (README: rgraph serve). Stops on "
    "SIGINT/SIGTERM.\n\n"
    "Every request needs a token: a random one per run, printed in the address (…/?token=TOKEN;\n"
    "the page keeps it as a cookie), or --token TOKEN. API clients send `Authorization: Bearer "
    "TOKEN`.\n"
    "A --host that is not a loopback address is refused unless --token is given.\n";

}  // namespace

int cmdServe(int argc, char** argv) {
    Args args;
    if (auto done = parseCommand(
            argc, argv, "serve",
            {"pipeline", "scene", "scene-arg", "set", "camera", "environment", "environment-sun",
             "variant", "size", "device", "port", "host", "token", "interval", "no-cache"},
            kHelp, args))
        return *done;
    ServeOptions so;
    uint32_t port = 8080, interval = 100;
    if (args.has("port") &&
        (!parseCount(args.get("port"), port, /*allowZero=*/true) || port > 65535))
        return usageError("--port must be a TCP port in 0..65535 (0: any free port)", "serve");
    if (args.has("interval") && !parseCount(args.get("interval"), interval))
        return usageError("--interval must be milliseconds", "serve");
    so.port = static_cast<int>(port);
    so.frameIntervalMs = interval;
    if (args.has("host")) so.host = args.get("host");
    if (args.has("token")) {
        so.token = args.get("token");
        so.tokenGiven = true;
        if (so.token.empty()) return usageError("--token must not be empty", "serve");
    }
    if (isBuiltin(pipelineArg(args))) return usageError("serve needs a pipeline script", "serve");
    auto setup = setupRun(args, "serve", 1, {}, /*verbose=*/false);
    if (!setup) return report(setup.error());
    so.pipeline = setup->pipeline;
    return serve(*setup->runtime, *setup->session, so);
}

}  // namespace rg::cli

// `rgraph serve`: renders a pipeline continuously (headless) and serves a page and a JSON API to
// look at and reconfigure it while it runs — the compiled graph, per-pass timings, every
// parameter and pass switch as a control, any resource as an image, script errors with
// file:line while the last good plan keeps rendering, scripts reloaded as `watch` does.
#pragma once

#include <string>

#include "runtime/session.h"

namespace rg {

struct ServeOptions {
    std::string host =
        "127.0.0.1";  // loopback unless asked otherwise (then only with a token given)
    // Every request needs this token (README: rgraph serve); without tokenGiven a random one is
    // made per run and printed in the address.
    std::string token;
    bool tokenGiven = false;
    int port = 8080;                 // 0: any free port (printed)
    std::string pipeline;            // the script (reloaded when it or its files change)
    uint32_t frameIntervalMs = 100;  // pause between frames
    uint32_t pollMs = 300;           // how often the pipeline's files are checked
};

// Serves until SIGINT or SIGTERM; returns the process exit code (0 after a signal, within a
// second or two: requests still waiting are answered 503 "shutting down"). Prints
// "rgraph serve: http://HOST:PORT/?token=TOKEN" once listening.
int serve(Runtime& runtime, Session& session, const ServeOptions& options);

}  // namespace rg

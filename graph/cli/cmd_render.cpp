// `rgraph render`: a pipeline's frames to EXR (linear) and PNG (display).
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

#include "cli.h"

namespace rg::cli {

namespace {

const char* const kHelp =
    "usage: rgraph render [--pipeline FILE.lua|builtin:NAME] [--scene FILE] [--camera NAME] "
    "[--size WxH] [--frames N|A..B [--warmup W]]\n"
    "                     [--out FILE.exr] [--png FILE.png] [--capture "
    "RESOURCE|gbuffer.CHANNEL]... [--view VIEW]\n"
    "                     [--scene-arg NAME=VALUE]... [--set NAME=VALUE]... [--environment "
    "FILE|sky|none] [--device N] [--verbose]\n"
    "                     [--no-cache]\n\n"
    "--scene: a Lua scene (scripts/scenes/*.lua), .gltf or .glb (default "
    "scripts/scenes/default.lua).\n" RG_HELP_ENVIRONMENT RG_HELP_SCENE_ARGS_AND_SET
    "--view: write a debug view instead of the image: normals, basecolor, smoothness, metalmask,\n"
    "materialid, reflectance, ao, emissive, stencil, lights, ssao (screen-space AO), ssr, "
    "ssr_confidence,\nreflection (SSR and the probes composed), probes (which local light probe "
    "reflects each pixel), cascades (the sun's shadow cascades), shadow (its map) or shadow:LIGHT "
    "(a local light's maps),\n"
    "lightmap (the baked lightmap's irradiance at each pixel's normal), sgN (its lobe N), or a "
    "view "
    "the pipeline declares\nwith rg.view (scripts/views.lua, scripts/README.md).\n"
    "--capture gbuffer.CHANNEL: a G-buffer channel, decoded, as an EXR layer (e.g. "
    "gbuffer.normal).\n"
    "Renders N frames (default 1) at WxH (default 1280x720) through the pipeline (default\n"
    "scripts/pipelines/deferred.lua), calling its rg.frame(ctx) before each frame. Writes FILE.png "
    "(default\n"
    "FILE.exr's path with .png, else out/render.png), the display image, and FILE.exr (default "
    "out/render.exr; other\n"
    "extensions are refused), linear: layer 'hdr' holds\n"
    "absolute luminance in cd/m2 (pre-exposure divided out) when the pipeline has a camera "
    "(rg.output\n"
    "{ display, hdr, exposure }), else the output itself. Each --capture adds that resource as a "
    "layer of\n"
    "its name. Both files record the camera settings and exposure in their metadata.\n"
    "--frames A..B renders frames A to B (0-based) of the sequence the pipeline's rg.frame "
    "scripts\n"
    "(ctx.frame and ctx.time = frame / 60 s as in one run from 0) and writes each: a run of '#' in "
    "--out\n"
    "and --png is the frame number (shot.####.exr), else .NNNN goes before the extension. "
    "--warmup W first\n"
    "renders the W frames before A unwritten, for pipelines whose frames carry history (SSR's "
    "previous\n"
    "frame, exposure, the reference mode's accumulation): with W = A a range is bit-identical to "
    "those frames\n"
    "of one run from 0, so ranges can render on many machines (tools/farm.py render).\n"
    "The passes that run once per build (cadence = \"once\": environment filtering, probe capture, "
    "lookup\n"
    "tables) restore their outputs from the cache folder (RG_CACHE_DIR)/once when the same passes, "
    "shaders,\n"
    "scene and device made them before, and save them there otherwise; --no-cache always records "
    "them.\n";

}  // namespace

int cmdRender(int argc, char** argv) {
    Args args;
    if (auto done = parseCommand(argc, argv, "render",
                                 {"pipeline", "scene", "scene-arg", "set", "camera", "environment",
                                  "environment-sun", "variant", "size", "frames", "warmup", "out",
                                  "png", "capture", "view", "device", "verbose", "no-cache"},
                                 kHelp, args))
        return *done;
    const auto captures = args.all("capture");
    auto paths = outputPaths(args, "out/render.exr");
    if (!paths) return report(paths.error());
    using Clock = std::chrono::steady_clock;
    const auto ms = [](Clock::time_point a, Clock::time_point b) {
        return std::chrono::duration<double, std::milli>(b - a).count();
    };
    const auto t0 = Clock::now();
    auto setup = setupRun(args, "render", 1, captures, args.has("verbose"));
    if (!setup) return report(setup.error());
    Runtime& rt = *setup->runtime;
    const auto t1 = Clock::now();
    // Progress on stderr: one updating line on a terminal, else a line per tenth of the frames.
    const bool tty = isatty(fileno(stderr));
    const uint32_t step = std::max(1u, setup->frames / 10);
    const auto [exrPath, pngPath] = *paths;
    Result<Image> written = Image{};
    uint32_t writtenFrames = 0;
    for (uint32_t f = 0; f < setup->frames; ++f) {
        if (auto r = setup->frame(); !r) return report(r.error());
        if (setup->frames > 1 && !args.has("verbose") &&
            (tty || (f + 1) % step == 0 || f + 1 == setup->frames))
            std::fprintf(stderr, tty ? "\rrgraph: frame %u/%u" : "rgraph: frame %u/%u\n", f + 1,
                         setup->frames);
        const uint64_t number = setup->lastFrameNumber();
        if (setup->range && number >= setup->rangeStart) {  // a sequence's frame: written now
            written = writeOutputs(*setup, framePath(exrPath, number), framePath(pngPath, number),
                                   captures);
            if (!written) return report(written.error());
            ++writtenFrames;
        }
    }
    if (setup->frames > 1 && !args.has("verbose") && tty) std::fprintf(stderr, "\n");
    if (auto r = rt.gpu().waitIdle(); !r)
        return report(r.error());  // the frames' work, for the timings
    const auto t2 = Clock::now();
    if (!setup->range) written = writeOutputs(*setup, exrPath, pngPath, captures);
    if (!written) return report(written.error());
    const Image* out = &*written;
    if (const auto& once = rt.executor().onceCacheStats();
        args.has("verbose") && (once.restoredPasses || once.savedPasses))
        std::fprintf(stderr,
                     once.restoredPasses
                         ? "rgraph: once-per-build passes: %u restored from %s (%.0f ms)\n"
                         : "rgraph: once-per-build passes: %u recorded, saved to %s (%.0f ms)\n",
                     once.restoredPasses ? once.restoredPasses : once.savedPasses,
                     once.file.c_str(), once.restoredPasses ? once.restoreMs : once.saveMs);
    if (args.has("verbose"))
        std::fprintf(stderr,
                     "rgraph: timings: device %.0f ms, pipeline and scene load %.0f ms, %u frame%s "
                     "%.0f ms, writing %.0f ms\n",
                     setup->deviceMs, ms(t0, t1) - setup->deviceMs, setup->frames,
                     setup->frames == 1 ? "" : "s", ms(t1, t2), ms(t2, Clock::now()));
    if (setup->range)
        std::printf(
            "rgraph: wrote frames %llu..%llu: %s .. %s and PNGs (%ux%u, %u written, %u "
            "warm-up, %s)\n",
            static_cast<unsigned long long>(setup->rangeStart),
            static_cast<unsigned long long>(setup->lastFrameNumber()),
            framePath(exrPath, setup->rangeStart).c_str(),
            framePath(exrPath, setup->lastFrameNumber()).c_str(), out->width, out->height,
            writtenFrames, setup->frames - writtenFrames, rt.gpu().deviceInfo().name.c_str());
    else
        std::printf("rgraph: wrote %s and %s (%ux%u, %u frame%s, %s)\n", exrPath.c_str(),
                    pngPath.c_str(), out->width, out->height, setup->frames,
                    setup->frames == 1 ? "" : "s", rt.gpu().deviceInfo().name.c_str());
    if (rt.gpu().validationMessageCount() > 0) {
        std::fprintf(stderr, "rgraph: %u validation message(s)\n",
                     rt.gpu().validationMessageCount());
        return kFailed;
    }
    return kOk;
}

}  // namespace rg::cli

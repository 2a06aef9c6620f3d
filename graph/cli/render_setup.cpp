// What render, bench, watch and serve share: the runtime and session a command renders with, and
// the EXR/PNG outputs it writes.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <future>
#include <map>
#include <string>
#include <vector>

#include "lua/lua_host.h"
#include "cli.h"

namespace rg::cli {

// Shared by render, bench and watch: options, runtime, pipeline load and build.
Result<RenderSetup> setupRun(const Args& args, const char* command, uint32_t defaultFrames,
                             const std::vector<std::string>& captures, bool verbose) {
    RenderSetup s;
    s.frames = defaultFrames;
    s.pipeline = pipelineArg(args);
    CompileOptions opts;
    if (args.has("size") && !parseSize(args.get("size"), opts.outputWidth, opts.outputHeight))
        return fail(
            ErrorCode::InvalidInput,
            std::string(command) +
                ": --size must be WIDTHxHEIGHT with each side in 1..16384, e.g. 1280x720; got '" +
                args.get("size") + "'");
    const bool render = std::string(command) == "render";
    if (const std::string f = args.get("frames"); render && f.find("..") != std::string::npos) {
        // A..B: frames A to B of the sequence, after --warmup W unwritten frames before A.
        uint32_t a = 0, b = 0, warmup = 0;
        const auto dots = f.find("..");
        if (!parseCount(f.substr(0, dots), a, true) || !parseCount(f.substr(dots + 2), b, true) ||
            b < a)
            return fail(ErrorCode::InvalidInput,
                        "render: --frames A..B needs whole numbers 0 <= A <= B, got '" + f + "'");
        if (args.has("warmup") && !parseCount(args.get("warmup"), warmup, true))
            return fail(ErrorCode::InvalidInput,
                        "render: --warmup must be a whole number of frames, got '" +
                            args.get("warmup") + "'");
        if (warmup > a)
            return fail(ErrorCode::InvalidInput,
                        "render: --warmup " + std::to_string(warmup) + " reaches before frame 0 (" +
                            "the range starts at " + std::to_string(a) + ")");
        s.range = true;
        s.rangeStart = a;
        s.firstFrame = a - warmup;
        s.frames = b - a + 1 + warmup;
    } else if (args.has("frames") && !parseCount(args.get("frames"), s.frames)) {
        return fail(ErrorCode::InvalidInput, std::string(command) +
                                                 ": --frames must be a positive whole number" +
                                                 (render ? " or a range A..B" : ""));
    } else if (args.has("warmup")) {
        return fail(ErrorCode::InvalidInput, "render: --warmup goes with --frames A..B");
    }
    RuntimeOptions ro;
    if (args.has("device")) {
        const std::string v = args.get("device");
        if (v.empty() || v.size() > 3 || v.find_first_not_of("0123456789") != std::string::npos)
            return fail(
                ErrorCode::InvalidInput,
                std::string(command) + ": --device must be a device index (see 'rgraph devices')");
        ro.device = static_cast<uint32_t>(std::stoul(v));
    }
    if (args.has("scene") && isBuiltin(s.pipeline))
        return fail(ErrorCode::InvalidInput,
                    std::string(command) + ": --scene: built-in graphs draw no scene");
    const auto started = std::chrono::steady_clock::now();
    auto rt = Runtime::create(ro);
    if (!rt) return std::unexpected(rt.error());
    s.runtime = std::move(*rt);
    s.deviceMs =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - started)
            .count();
    if (isBuiltin(s.pipeline)) {
        auto graph = builtinGraph(s.pipeline.substr(8));
        if (!graph) return std::unexpected(graph.error());
        for (const auto& c : captures) {
            auto it = std::find_if(graph->resources.begin(), graph->resources.end(),
                                   [&](auto& r) { return r.name == c; });
            if (it == graph->resources.end())
                return fail(ErrorCode::NotFound, "--capture: no resource named '" + c + "'");
            it->exported = true;
        }
        if (auto r = s.runtime->executor().build(*graph, opts); !r)
            return std::unexpected(r.error());
        s.runtime->executor().setFrameNumberBase(s.firstFrame);
        return s;
    }
    SessionOptions so;
    so.bakeLightmap = bake::bakeLightmap;
    so.compile = opts;
    so.captures = captures;
    so.scene = args.get("scene");
    so.view = args.get("view");
    so.camera = args.get("camera");
    so.environment = args.get("environment");
    so.environmentSun = args.get("environment-sun");
    so.variant = args.get("variant");
    so.verbose = verbose;
    so.firstFrame = s.firstFrame;
    so.warnings = true;  // what a scene's loader skipped, always (Scene::warnings)
    // The once-per-build outputs' disk cache: not for bench, whose first-frame column times those passes.
    if (std::string(command) != "bench" && !args.has("no-cache")) so.onceCache = cacheDir();
    // NAME=VALUE pairs: --scene-arg for the scene script's `scene.args`, --set for pipeline parameters.
    auto pair = [&](const std::string& option,
                    const std::string& text) -> Result<std::pair<std::string, std::string>> {
        const auto eq = text.find('=');
        if (eq == std::string::npos || eq == 0)
            return fail(ErrorCode::InvalidInput, std::string(command) + ": --" + option +
                                                     " takes NAME=VALUE, got '" + text + "'");
        return std::pair{text.substr(0, eq), text.substr(eq + 1)};
    };
    for (const auto& a : args.all("scene-arg")) {
        auto p = pair("scene-arg", a);
        if (!p) return std::unexpected(p.error());
        so.sceneArgs[p->first] = p->second;
    }
    for (const auto& a : args.all("set")) {
        auto p = pair("set", a);
        if (!p) return std::unexpected(p.error());
        char* end = nullptr;
        const double number = std::strtod(p->second.c_str(), &end);
        if (!p->second.empty() && end && *end == '\0' && std::isfinite(number))
            so.params[p->first] = Value(number);
        else if (p->second == "true" || p->second == "false")
            so.params[p->first] = Value(p->second == "true");
        else
            so.params[p->first] = Value(p->second);
    }
    s.session = std::make_unique<Session>(*s.runtime, so);
    if (auto r = s.session->load(s.pipeline); !r) return std::unexpected(r.error());
    return s;
}

// A file as the outputs name it: relative to the project root when inside it
// ("scripts/pipelines/deferred.lua"), else its file name — never a machine path.
std::string logicalName(const std::string& path) {
    if (isBuiltin(path)) return path;
    std::error_code ec;
    const fs::path abs = fs::weakly_canonical(fs::absolute(path, ec), ec);
    const fs::path root = fs::weakly_canonical(fs::path(projectRoot()), ec);
    const fs::path rel = abs.lexically_relative(root);
    if (!rel.empty() && *rel.begin() != "..") return rel.generic_string();
    return abs.filename().string();
}

std::string exrMetaDevice(Runtime& rt) {
    return rt.gpu().deviceInfo().name + " (" + rt.gpu().deviceInfo().driver + ")";
}

std::vector<std::string> rgbaNames(uint32_t n) {
    static const char* rgba[] = {"R", "G", "B", "A"};
    std::vector<std::string> names;
    for (uint32_t i = 0; i < n; ++i) names.push_back(rgba[i]);
    return names;
}

std::string number(double v) {
    char b[32];
    std::snprintf(b, sizeof b, "%.6g", v);
    return b;
}

// Writes the EXR (linear: layer `hdr` in cd/m² when the pipeline has a physical camera, plus one
// layer per capture) and the PNG (the display image). Returns the display image.
Result<Image> writeOutputs(RenderSetup& setup, const std::string& exrPath,
                           const std::string& pngPath, const std::vector<std::string>& captures) {
    gpu::Executor& ex = setup.runtime->executor();
    const std::string displayName =
        setup.session ? setup.session->displayResource() : setup.output();
    const bool view = setup.session && displayName != setup.output();
    auto display = ex.readback(displayName);
    if (!display) return std::unexpected(display.error());
    ExrWriteOptions eo;
    eo.metadata["rgraph.pipeline"] = logicalName(setup.pipeline);
    eo.metadata["rgraph.device"] = exrMetaDevice(*setup.runtime);
    if (setup.range)  // the frame this file holds (how many ran before it depends on the warm-up)
        eo.ints["rgraph.frame"] = static_cast<int>(setup.lastFrameNumber());
    else
        eo.ints["rgraph.frames"] = static_cast<int>(setup.frames);
    std::vector<ImageLayer> layers;
    const PipelineDesc* pipeline = setup.session ? &setup.session->pipeline() : nullptr;
    Image png = *display;
    if (view) {
        // A debug view is display-ready; the EXR gets it as is.
        layers.push_back({"view", rgbaNames(display->channels), *display});
    } else if (pipeline && !pipeline->hdr.empty()) {
        // Absolute luminance: the pre-exposure this frame was rendered with divided out.
        auto hdr = readAbsoluteHdr(ex, *pipeline);
        if (!hdr) return std::unexpected(hdr.error());
        layers.push_back({"hdr", rgbaNames(hdr->image.channels), hdr->image});
        eo.floats["rgraph.ev100"] = hdr->ev100;
        eo.floats["rgraph.exposure"] = hdr->exposure;
        eo.floats["rgraph.preExposure"] = hdr->preExposure;
        for (const char* p :
             {"exposure_mode", "aperture", "shutter", "iso", "ec", "tonemap", "bloom_mix_stops"})
            if (const ParamDesc* d = pipeline->findParam(p)) {
                const std::string key = std::string("rgraph.camera.") + p;
                if (d->value.isString())
                    eo.metadata[key] = d->value.asString();
                else
                    eo.floats[key] = static_cast<float>(d->value.asNumber());
            }
    } else {
        layers.push_back({"hdr", rgbaNames(display->channels), *display});
        // A pipeline without a camera: its output is shown clamped, sRGB-encoded.
        for (size_t i = 0; i < png.pixels.size(); ++i)
            png.pixels[i] = srgbEncode(std::clamp(png.pixels[i], 0.0f, 1.0f));
    }
    // G-buffer channels, decoded on the CPU with the layout's own unpack code.
    std::vector<std::string> channelNames;
    if (setup.session)
        for (const auto& ch : setup.session->channelCaptures()) {
            channelNames.push_back(ch.name);
            auto out = setup.session->channelImage(ch);
            if (!out) return std::unexpected(out.error());
            const uint32_t comps = out->channels;
            static const char* xyz[] = {"x", "y", "z", "w"};
            std::vector<std::string> names;
            for (uint32_t c = 0; c < comps; ++c) names.push_back(comps == 1 ? "Y" : xyz[c]);
            layers.push_back({ch.name, names, std::move(*out)});
        }
    for (const auto& c : captures) {
        if (c == setup.output() || (pipeline && c == pipeline->hdr)) continue;
        if (std::find(channelNames.begin(), channelNames.end(), c) != channelNames.end()) continue;
        auto img = ex.readback(c);
        if (!img) return std::unexpected(img.error());
        layers.push_back({c, rgbaNames(img->channels), *img});
    }
    for (const auto& p : {exrPath, pngPath}) {
        std::error_code ec;
        if (auto parent = fs::path(p).parent_path(); !parent.empty())
            fs::create_directories(parent, ec);
    }
    // Half floats end at 65504: absolute luminance beyond it (the sun, its mirror reflections)
    // would be written as inf, so such a file is written in 32-bit floats.
    for (const auto& l : layers)
        for (float v : l.image.pixels)
            if (std::isfinite(v) && std::abs(v) > 65504.0f) eo.pixelType = ExrPixelType::Float;
    Image rgb(png.width, png.height, std::min(3u, png.channels));
    for (size_t i = 0; i < size_t(png.width) * png.height; ++i)
        for (uint32_t c = 0; c < rgb.channels; ++c)
            rgb.pixels[i * rgb.channels + c] = png.pixels[i * png.channels + c];
    std::map<std::string, std::string> text;
    for (const auto& [k, v] : eo.metadata) text[k] = v;
    // The two files at once: the PNG's compression on a thread of its own beside the EXR's.
    auto pngWritten = std::async(std::launch::async, [&] { return writePng(pngPath, rgb, text); });
    auto exrWritten = writeExr(exrPath, layers, eo);
    auto pngResult = pngWritten.get();
    if (!exrWritten) return std::unexpected(exrWritten.error());
    if (!pngResult) return std::unexpected(pngResult.error());
    return *display;
}

// The EXR and PNG paths a command writes: --out FILE.exr (default `defaultExr`), and --png
// FILE.png or, without it, the EXR's path with .png — so an explicit --out never writes into the
// default folder. Other extensions are refused rather than written under a wrong name.
std::string framePath(const std::string& path, uint64_t frame) {
    const size_t slash = path.find_last_of('/');
    const size_t nameStart = slash == std::string::npos ? 0 : slash + 1;
    const size_t hash = path.find('#', nameStart);
    if (hash != std::string::npos) {
        size_t end = hash;
        while (end < path.size() && path[end] == '#') ++end;
        std::string digits = std::to_string(frame);
        if (digits.size() < end - hash) digits.insert(0, end - hash - digits.size(), '0');
        return path.substr(0, hash) + digits + path.substr(end);
    }
    const size_t dot = path.find_last_of('.');
    char number[32];
    std::snprintf(number, sizeof number, ".%04llu", static_cast<unsigned long long>(frame));
    if (dot == std::string::npos || dot < nameStart) return path + number;
    return path.substr(0, dot) + number + path.substr(dot);
}

Result<std::pair<std::string, std::string>> outputPaths(const Args& args,
                                                        const std::string& defaultExr) {
    auto endsWith = [](std::string path, const std::string& ext) {
        std::transform(path.begin(), path.end(), path.begin(),
                       [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
        return path.size() > ext.size() &&
               path.compare(path.size() - ext.size(), ext.size(), ext) == 0;
    };
    const std::string exr = args.get("out", defaultExr);
    if (!endsWith(exr, ".exr"))
        return fail(ErrorCode::InvalidInput, "--out: '" + exr +
                                                 "' is not an .exr path (rgraph writes OpenEXR "
                                                 "there; the PNG goes beside it, or to --png)");
    std::string png = args.has("png") ? args.get("png") : exr.substr(0, exr.size() - 4) + ".png";
    if (!endsWith(png, ".png"))
        return fail(ErrorCode::InvalidInput, "--png: '" + png + "' is not a .png path");
    return std::pair{exr, png};
}

}  // namespace rg::cli

// rgraph: the command line. Exit codes: 0 success, 1 a failed check or a device failure,
// 2 bad usage or bad input.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <future>
#include <cmath>
#include <cstring>
#include <unistd.h>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bake/lightmap.h"
#include "core/compiler.h"
#include "image/image.h"
#include "layout/layout.h"
#include "scene/environment.h"
#include "scene/scene.h"
#include "golden/command.h"
#include "golden/metrics.h"
#include "accuracy.h"
#include "runtime.h"
#include "file_watch.h"
#include "serve.h"
#include "session.h"

#include <thread>

namespace fs = std::filesystem;
using namespace rg;

namespace {

constexpr int kOk = 0, kFailed = 1, kUsage = 2;

int exitCodeOf(const Error& e) {
    switch (e.code) {
    case ErrorCode::InvalidInput:
    case ErrorCode::NotFound:
    case ErrorCode::Unsupported: return kUsage;
    default: return kFailed;
    }
}

int report(const Error& e) {
    std::fprintf(stderr, "rgraph: error: %s\n", e.describe().c_str());
    return exitCodeOf(e);
}

int usageError(const std::string& msg, const char* command) {
    std::fprintf(stderr, "rgraph %s: %s (see 'rgraph %s --help')\n", command, msg.c_str(), command);
    return kUsage;
}

// A tiny argument reader: --flag VALUE, --flag=VALUE, repeated flags, --help.
struct Args {
    std::map<std::string, std::vector<std::string>> values;
    bool help = false;
    std::string error;

    static Args parse(int argc, char** argv, int first, const std::vector<std::string>& known) {
        static const std::vector<std::string> flags = {"verbose", "floors", "rebake", "no-cache"};  // options without a value
        Args a;
        for (int i = first; i < argc; ++i) {
            std::string arg = argv[i];
            if (arg == "--help" || arg == "-h") {
                a.help = true;
                continue;
            }
            if (arg.rfind("--", 0) != 0) {
                a.values[""].push_back(arg);
                continue;
            }
            std::string name = arg.substr(2), value;
            if (std::find(flags.begin(), flags.end(), name) != flags.end() &&
                std::find(known.begin(), known.end(), name) != known.end()) {
                a.values[name].push_back("1");
                continue;
            }
            const auto eq = name.find('=');
            if (eq != std::string::npos) {
                value = name.substr(eq + 1);
                name = name.substr(0, eq);
            }
            if (std::find(known.begin(), known.end(), name) == known.end()) {
                a.error = "unknown option --" + name;
                return a;
            }
            if (eq == std::string::npos) {
                if (i + 1 >= argc) {
                    a.error = "option --" + name + " needs a value";
                    return a;
                }
                value = argv[++i];
            }
            a.values[name].push_back(value);
        }
        return a;
    }
    bool has(const std::string& k) const { return values.count(k) > 0; }
    std::string get(const std::string& k, const std::string& def = "") const {
        auto it = values.find(k);
        return it == values.end() ? def : it->second.back();
    }
    std::vector<std::string> all(const std::string& k) const {
        auto it = values.find(k);
        return it == values.end() ? std::vector<std::string>{} : it->second;
    }
};

bool parseSize(const std::string& s, uint32_t& w, uint32_t& h) {
    unsigned a = 0, b = 0;
    char x = 0;
    if (std::sscanf(s.c_str(), "%u%c%u", &a, &x, &b) != 3 || (x != 'x' && x != 'X') || a == 0 || b == 0 ||
        a > 16384 || b > 16384)
        return false;
    w = a;
    h = b;
    return true;
}

bool parseCount(const std::string& s, uint32_t& n, bool allowZero = false) {
    char* end = nullptr;
    unsigned long v = std::strtoul(s.c_str(), &end, 10);
    if (s.empty() || s[0] == '-' || *end || (v == 0 && !allowZero) || v > 1000000) return false;
    n = static_cast<uint32_t>(v);
    return true;
}

std::string defaultPipeline() { return projectRoot() + "/scripts/pipelines/deferred.lua"; }
std::string pipelineArg(const Args& args) { return args.get("pipeline", defaultPipeline()); }
bool isBuiltin(const std::string& p) { return p.rfind("builtin:", 0) == 0; }

// The graph a command works on, without a GPU: a pipeline script or builtin:NAME.
Result<GraphDesc> loadGraph(const Args& args) {
    std::string pipeline = pipelineArg(args);
    if (isBuiltin(pipeline)) return builtinGraph(pipeline.substr(8));
    LuaHost host(luaHostOptionsWithoutDevice());
    auto p = host.load(pipeline);
    if (!p) return std::unexpected(p.error());
    return graphWithParams(*p);
}

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
    "  test      run the golden-image tests (tests/golden/*.lua): --update, --report DIR, --junit FILE\n"
    "  compare   error between two EXR renders: relative error, RMSE, PSNR, heat map\n"
    "\n"
    "'rgraph COMMAND --help' describes each command. Exit codes: 0 success, 1 failed check or\n"
    "device failure, 2 bad usage or bad input.\n"
    "Environment: RG_VALIDATION=1 turns on the Vulkan validation layer; RG_CACHE_DIR moves the\n"
    "shader caches; RG_ROOT points at the project folder (shaders/, scripts/).\n";

int cmdDevices(int argc, char** argv) {
    Args args = Args::parse(argc, argv, 2, {});
    if (args.help) {
        std::printf("usage: rgraph devices\n\nLists the Vulkan devices; '*' marks the one rgraph chooses\n"
                    "(discrete GPU, then integrated, then CPU). Use --device N with other commands to override.\n");
        return kOk;
    }
    if (!args.error.empty()) return usageError(args.error, "devices");
    prepareEnvironment();
    auto devices = gpu::Context::listDevices();
    if (!devices) return report(devices.error());
    int chosen = -1, bestRank = 99;
    auto rank = [](const std::string& t) {
        return t == "discrete" ? 0 : t == "integrated" ? 1 : t == "virtual" ? 2 : t == "cpu" ? 3 : 4;
    };
    for (const auto& d : *devices)
        if (d.usable && rank(d.type) < bestRank) bestRank = rank(d.type), chosen = static_cast<int>(d.index);
    for (const auto& d : *devices) {
        std::printf("%c %u  %-40s %-10s Vulkan %u.%u.%u  %s%s%s\n", static_cast<int>(d.index) == chosen ? '*' : ' ',
                    d.index, d.name.c_str(), d.type.c_str(), VK_API_VERSION_MAJOR(d.apiVersion),
                    VK_API_VERSION_MINOR(d.apiVersion), VK_API_VERSION_PATCH(d.apiVersion), d.driver.c_str(),
                    d.usable ? "" : "  (unusable: ", d.usable ? "" : (d.whyNot + ")").c_str());
    }
    if (devices->empty()) {
        std::fprintf(stderr, "rgraph: no Vulkan devices (install mesa-vulkan-drivers for lavapipe)\n");
        return kFailed;
    }
    return kOk;
}

int cmdGraph(int argc, char** argv) {
    Args args = Args::parse(argc, argv, 2, {"pipeline", "format", "size", "capture"});
    if (args.help) {
        std::printf("usage: rgraph graph [--pipeline FILE.lua|builtin:NAME] [--format dot|json|materials] [--size WxH] [--capture RESOURCE]...\n\n"
                    "Compiles the pipeline (no GPU needed; memory sizes are estimated) and prints the plan:\n"
                    "passes in order, culled passes and why, resources with lifetimes and memory offsets,\n"
                    "barriers. Default format: dot. '--format materials' prints the material system instead:\n"
                    "each material's id, layout, lighting path and stencil value, how they were assigned,\n"
                    "and how many ids and stencil classes are left.\n");
        return kOk;
    }
    if (!args.error.empty()) return usageError(args.error, "graph");
    std::string format = args.get("format", "dot");
    if (format != "dot" && format != "json" && format != "materials")
        return usageError("--format must be 'dot', 'json' or 'materials'", "graph");
    if (format == "materials") {
        const std::string pipeline = pipelineArg(args);
        if (isBuiltin(pipeline)) return usageError("--format materials: built-in graphs declare no materials", "graph");
        LuaHost host(luaHostOptionsWithoutDevice());
        auto p = host.load(pipeline);
        if (!p) return report(p.error());
        std::printf("%s", describeMaterialSystem(*p).c_str());
        return kOk;
    }
    CompileOptions opts;
    if (args.has("size") && !parseSize(args.get("size"), opts.outputWidth, opts.outputHeight))
        return usageError("--size must be WIDTHxHEIGHT with each side in 1..16384, e.g. 1280x720; got '" + args.get("size") + "'", "graph");
    auto graph = loadGraph(args);
    if (!graph) return report(graph.error());
    for (const auto& c : args.all("capture")) {
        auto it = std::find_if(graph->resources.begin(), graph->resources.end(), [&](auto& r) { return r.name == c; });
        if (it == graph->resources.end()) return report(Error(ErrorCode::NotFound, "--capture: no resource named '" + c + "'"));
        it->exported = true;
    }
    auto plan = compile(*graph, opts);
    if (!plan) return report(plan.error());
    std::printf("%s\n", format == "dot" ? plan->toDot().c_str() : plan->toJson().c_str());
    return kOk;
}

struct RenderSetup {
    std::unique_ptr<Runtime> runtime;
    std::unique_ptr<Session> session;  // null for builtin:NAME graphs
    uint32_t frames = 1;
    std::string pipeline;
    double deviceMs = 0.0;  // Vulkan instance and device

    Result<void> frame() { return session ? session->frame() : runtime->executor().frame(); }
    std::string output() const { return session ? session->pipeline().output : "output"; }
};

// Shared by render, bench and watch: options, runtime, pipeline load and build.
Result<RenderSetup> setupRun(const Args& args, const char* command, uint32_t defaultFrames,
                             const std::vector<std::string>& captures, bool verbose = false) {
    RenderSetup s;
    s.frames = defaultFrames;
    s.pipeline = pipelineArg(args);
    CompileOptions opts;
    if (args.has("size") && !parseSize(args.get("size"), opts.outputWidth, opts.outputHeight))
        return fail(ErrorCode::InvalidInput, std::string(command) + ": --size must be WIDTHxHEIGHT with each side in 1..16384, e.g. 1280x720; got '" +
                                                 args.get("size") + "'");
    if (args.has("frames") && !parseCount(args.get("frames"), s.frames))
        return fail(ErrorCode::InvalidInput, std::string(command) + ": --frames must be a positive whole number");
    RuntimeOptions ro;
    if (args.has("device")) {
        const std::string v = args.get("device");
        if (v.empty() || v.size() > 3 || v.find_first_not_of("0123456789") != std::string::npos)
            return fail(ErrorCode::InvalidInput, std::string(command) + ": --device must be a device index (see 'rgraph devices')");
        ro.device = static_cast<uint32_t>(std::stoul(v));
    }
    if (args.has("scene") && isBuiltin(s.pipeline))
        return fail(ErrorCode::InvalidInput, std::string(command) + ": --scene: built-in graphs draw no scene");
    const auto started = std::chrono::steady_clock::now();
    auto rt = Runtime::create(ro);
    if (!rt) return std::unexpected(rt.error());
    s.runtime = std::move(*rt);
    s.deviceMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - started).count();
    if (isBuiltin(s.pipeline)) {
        auto graph = builtinGraph(s.pipeline.substr(8));
        if (!graph) return std::unexpected(graph.error());
        for (const auto& c : captures) {
            auto it = std::find_if(graph->resources.begin(), graph->resources.end(), [&](auto& r) { return r.name == c; });
            if (it == graph->resources.end()) return fail(ErrorCode::NotFound, "--capture: no resource named '" + c + "'");
            it->exported = true;
        }
        if (auto r = s.runtime->executor().build(*graph, opts); !r) return std::unexpected(r.error());
        return s;
    }
    SessionOptions so;
    so.compile = opts;
    so.captures = captures;
    so.scene = args.get("scene");
    so.view = args.get("view");
    so.camera = args.get("camera");
    so.environment = args.get("environment");
    so.verbose = verbose;
    // The once-per-build outputs' disk cache: not for bench, whose first-frame column times those passes.
    if (std::string(command) != "bench" && !args.has("no-cache")) so.onceCache = cacheDir();
    // NAME=VALUE pairs: --scene-arg for the scene script's `scene.args`, --set for pipeline parameters.
    auto pair = [&](const std::string& option, const std::string& text) -> Result<std::pair<std::string, std::string>> {
        const auto eq = text.find('=');
        if (eq == std::string::npos || eq == 0)
            return fail(ErrorCode::InvalidInput, std::string(command) + ": --" + option + " takes NAME=VALUE, got '" + text + "'");
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
        if (!p->second.empty() && end && *end == '\0' && std::isfinite(number)) so.params[p->first] = Value(number);
        else if (p->second == "true" || p->second == "false") so.params[p->first] = Value(p->second == "true");
        else so.params[p->first] = Value(p->second);
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

std::string exrMetaDevice(Runtime& rt) { return rt.gpu().deviceInfo().name + " (" + rt.gpu().deviceInfo().driver + ")"; }

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
Result<Image> writeOutputs(RenderSetup& setup, const std::string& exrPath, const std::string& pngPath,
                           const std::vector<std::string>& captures) {
    gpu::Executor& ex = setup.runtime->executor();
    const std::string displayName = setup.session ? setup.session->displayResource() : setup.output();
    const bool view = setup.session && displayName != setup.output();
    auto display = ex.readback(displayName);
    if (!display) return std::unexpected(display.error());
    ExrWriteOptions eo;
    eo.metadata["rgraph.pipeline"] = logicalName(setup.pipeline);
    eo.metadata["rgraph.device"] = exrMetaDevice(*setup.runtime);
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
        for (const char* p : {"exposure_mode", "aperture", "shutter", "iso", "ec", "tonemap", "bloom_ec"})
            if (const ParamDesc* d = pipeline->findParam(p)) {
                const std::string key = std::string("rgraph.camera.") + p;
                if (d->value.isString()) eo.metadata[key] = d->value.asString();
                else eo.floats[key] = static_cast<float>(d->value.asNumber());
            }
    } else {
        layers.push_back({"hdr", rgbaNames(display->channels), *display});
        // A pipeline without a camera: its output is shown clamped, sRGB-encoded.
        for (size_t i = 0; i < png.pixels.size(); ++i) png.pixels[i] = srgbEncode(std::clamp(png.pixels[i], 0.0f, 1.0f));
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
        if (auto parent = fs::path(p).parent_path(); !parent.empty()) fs::create_directories(parent, ec);
    }
    // Half floats end at 65504: absolute luminance beyond it (the sun, its mirror reflections)
    // would be written as inf, so such a file is written in 32-bit floats.
    for (const auto& l : layers)
        for (float v : l.image.pixels)
            if (std::isfinite(v) && std::abs(v) > 65504.0f) eo.pixelType = ExrPixelType::Float;
    Image rgb(png.width, png.height, std::min(3u, png.channels));
    for (size_t i = 0; i < size_t(png.width) * png.height; ++i)
        for (uint32_t c = 0; c < rgb.channels; ++c) rgb.pixels[i * rgb.channels + c] = png.pixels[i * png.channels + c];
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
Result<std::pair<std::string, std::string>> outputPaths(const Args& args, const std::string& defaultExr) {
    auto endsWith = [](std::string path, const std::string& ext) {
        std::transform(path.begin(), path.end(), path.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
        return path.size() > ext.size() && path.compare(path.size() - ext.size(), ext.size(), ext) == 0;
    };
    const std::string exr = args.get("out", defaultExr);
    if (!endsWith(exr, ".exr"))
        return fail(ErrorCode::InvalidInput, "--out: '" + exr + "' is not an .exr path (rgraph writes OpenEXR there; the PNG goes beside it, or to --png)");
    std::string png = args.has("png") ? args.get("png") : exr.substr(0, exr.size() - 4) + ".png";
    if (!endsWith(png, ".png")) return fail(ErrorCode::InvalidInput, "--png: '" + png + "' is not a .png path");
    return std::pair{exr, png};
}

int cmdRender(int argc, char** argv) {
    Args args = Args::parse(argc, argv, 2, {"pipeline", "scene", "scene-arg", "set", "camera", "environment", "size", "frames", "out", "png", "capture", "view", "device", "verbose", "no-cache"});
    if (args.help) {
        std::printf(
            "usage: rgraph render [--pipeline FILE.lua|builtin:NAME] [--scene FILE] [--camera NAME] [--size WxH] [--frames N]\n"
            "                     [--out FILE.exr] [--png FILE.png] [--capture RESOURCE|gbuffer.CHANNEL]... [--view VIEW]\n"
            "                     [--scene-arg NAME=VALUE]... [--set NAME=VALUE]... [--environment FILE|sky|none] [--device N] [--verbose]\n"
            "                     [--no-cache]\n\n"
            "--scene: a Lua scene (scripts/scenes/*.lua), .gltf or .glb (default scripts/scenes/default.lua).\n"
            "--environment FILE|sky|none: replaces the scene's environment (the distant light probe and the sky):\n"
            "an equirectangular .hdr/.exr in nits, the Preetham sky of the scene's sun, or none. A glTF scene\n"
            "with no light and no environment gets the sky, as glTF viewers light published models.\n"
            "--scene-arg NAME=VALUE (repeatable): sets scene.args.NAME for a Lua scene (a number when it reads as one).\n"
            "--set NAME=VALUE (repeatable): sets the pipeline parameter NAME (rg.param) before the first frame.\n"
            "--view: write a debug view instead of the image: normals, basecolor, smoothness, metalmask,\n"
            "materialid, reflectance, ao, emissive, stencil, lights, ssao (screen-space AO), ssr, ssr_confidence,\nreflection (SSR and the probes composed), probes (which local light probe reflects each pixel), cascades (the sun's shadow cascades), shadow (its map) or shadow:LIGHT (a local light's maps),\n"
            "lightmap (the baked lightmap's irradiance at each pixel's normal) or sgN (its lobe N).\n"
            "--capture gbuffer.CHANNEL: a G-buffer channel, decoded, as an EXR layer (e.g. gbuffer.normal).\n"
            "Renders N frames (default 1) at WxH (default 1280x720) through the pipeline (default\n"
            "scripts/pipelines/deferred.lua), calling its rg.frame(ctx) before each frame. Writes FILE.png (default\n"
            "FILE.exr's path with .png, else out/render.png), the display image, and FILE.exr (default out/render.exr; other\n"
            "extensions are refused), linear: layer 'hdr' holds\n"
            "absolute luminance in cd/m2 (pre-exposure divided out) when the pipeline has a camera (rg.output\n"
            "{ display, hdr, exposure }), else the output itself. Each --capture adds that resource as a layer of\n"
            "its name. Both files record the camera settings and exposure in their metadata.\n"
            "The passes that run once per build (cadence = \"once\": environment filtering, probe capture, lookup\n"
            "tables) restore their outputs from the cache folder (RG_CACHE_DIR)/once when the same passes, shaders,\n"
            "scene and device made them before, and save them there otherwise; --no-cache always records them.\n");
        return kOk;
    }
    if (!args.error.empty()) return usageError(args.error, "render");
    const auto captures = args.all("capture");
    auto paths = outputPaths(args, "out/render.exr");
    if (!paths) return report(paths.error());
    using Clock = std::chrono::steady_clock;
    const auto ms = [](Clock::time_point a, Clock::time_point b) { return std::chrono::duration<double, std::milli>(b - a).count(); };
    const auto t0 = Clock::now();
    auto setup = setupRun(args, "render", 1, captures, args.has("verbose"));
    if (!setup) return report(setup.error());
    Runtime& rt = *setup->runtime;
    const auto t1 = Clock::now();
    // Progress on stderr: one updating line on a terminal, else a line per tenth of the frames.
    const bool tty = isatty(fileno(stderr));
    const uint32_t step = std::max(1u, setup->frames / 10);
    for (uint32_t f = 0; f < setup->frames; ++f) {
        if (auto r = setup->frame(); !r) return report(r.error());
        if (setup->frames > 1 && !args.has("verbose") && (tty || (f + 1) % step == 0 || f + 1 == setup->frames))
            std::fprintf(stderr, tty ? "\rrgraph: frame %u/%u" : "rgraph: frame %u/%u\n", f + 1, setup->frames);
    }
    if (setup->frames > 1 && !args.has("verbose") && tty) std::fprintf(stderr, "\n");
    const auto [exrPath, pngPath] = *paths;
    if (auto r = rt.gpu().waitIdle(); !r) return report(r.error());  // the frames' work, for the timings
    const auto t2 = Clock::now();
    auto written = writeOutputs(*setup, exrPath, pngPath, captures);
    if (!written) return report(written.error());
    const Image* out = &*written;
    if (const auto& once = rt.executor().onceCacheStats(); args.has("verbose") && (once.restoredPasses || once.savedPasses))
        std::fprintf(stderr, once.restoredPasses ? "rgraph: once-per-build passes: %u restored from %s (%.0f ms)\n"
                                                 : "rgraph: once-per-build passes: %u recorded, saved to %s (%.0f ms)\n",
                     once.restoredPasses ? once.restoredPasses : once.savedPasses, once.file.c_str(),
                     once.restoredPasses ? once.restoreMs : once.saveMs);
    if (args.has("verbose"))
        std::fprintf(stderr, "rgraph: timings: device %.0f ms, pipeline and scene load %.0f ms, %u frame%s %.0f ms, writing %.0f ms\n",
                     setup->deviceMs, ms(t0, t1) - setup->deviceMs, setup->frames, setup->frames == 1 ? "" : "s", ms(t1, t2), ms(t2, Clock::now()));
    std::printf("rgraph: wrote %s and %s (%ux%u, %u frame%s, %s)\n", exrPath.c_str(), pngPath.c_str(), out->width,
                out->height, setup->frames, setup->frames == 1 ? "" : "s", rt.gpu().deviceInfo().name.c_str());
    if (rt.gpu().validationMessageCount() > 0) {
        std::fprintf(stderr, "rgraph: %u validation message(s)\n", rt.gpu().validationMessageCount());
        return kFailed;
    }
    return kOk;
}

int cmdWatch(int argc, char** argv) {
    Args args = Args::parse(argc, argv, 2, {"pipeline", "scene", "scene-arg", "set", "camera", "environment", "size", "out", "png", "device", "interval", "max-reloads", "no-cache"});
    if (args.help) {
        std::printf(
            "usage: rgraph watch [--pipeline FILE.lua] [--scene FILE] [--size WxH] [--out FILE.exr] [--png FILE.png]\n"
            "                    [--scene-arg NAME=VALUE]... [--set NAME=VALUE]... [--environment FILE|sky|none] [--interval MS] [--max-reloads N]\n\n"
            "--environment FILE|sky|none: replaces the scene's environment (the distant light probe and the sky):\n"
            "an equirectangular .hdr/.exr in nits, the Preetham sky of the scene's sun, or none. A glTF scene\n"
            "with no light and no environment gets the sky, as glTF viewers light published models.\n"
            "Renders once, then re-renders whenever a script or shader the pipeline uses changes (polled\n"
            "every MS milliseconds, default 250). A script that fails to load or compile is reported and the\n"
            "previous pipeline keeps running. Stops after N reloads when --max-reloads is given.\n");
        return kOk;
    }
    if (!args.error.empty()) return usageError(args.error, "watch");
    uint32_t interval = 250, maxReloads = 0;
    if (args.has("interval") && !parseCount(args.get("interval"), interval)) return usageError("--interval must be milliseconds", "watch");
    if (args.has("max-reloads") && !parseCount(args.get("max-reloads"), maxReloads)) return usageError("--max-reloads must be a count", "watch");
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
    std::printf("rgraph watch: rendered %s; watching %zu files\n", pngPath.c_str(), session.files().size());
    std::fflush(stdout);
    FileWatch watched;
    watched.changed(session.files());
    for (uint32_t reloads = 0; maxReloads == 0 || reloads < maxReloads;) {
        std::this_thread::sleep_for(std::chrono::milliseconds(interval));
        if (!watched.changed(session.files())) continue;
        ++reloads;
        if (auto r = session.load(setup->pipeline); !r) {
            std::printf("rgraph watch: reload failed, the previous pipeline keeps running:\n%s\n", r.error().describe().c_str());
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

int cmdServe(int argc, char** argv) {
    Args args = Args::parse(argc, argv, 2, {"pipeline", "scene", "scene-arg", "set", "camera", "environment", "size", "device", "port", "host", "token", "interval", "no-cache"});
    if (args.help) {
        std::printf(
            "usage: rgraph serve [--pipeline FILE.lua] [--scene FILE] [--size WxH] [--port N] [--host ADDRESS] [--token TOKEN] [--interval MS]\n"
            "                    [--scene-arg NAME=VALUE]... [--set NAME=VALUE]... [--environment FILE|sky|none]\n\n"
            "Renders the pipeline continuously (headless) and serves a page at http://HOST:PORT/ (default\n"
            "127.0.0.1:8080; --port 0 takes a free port; the address is printed) showing the compiled graph,\n"
            "per-pass GPU times, every parameter and pass switch as a control, any texture or G-buffer\n"
            "channel as an image with an exposure slider (EXR download), and script errors with file:line\n"
            "while the last good plan keeps rendering; scripts are reloaded when they change, as `watch`\n"
            "does. The page uses only the JSON API beneath it (README: rgraph serve). Stops on SIGINT/SIGTERM.\n\n"
            "Every request needs a token: a random one per run, printed in the address (…/?token=TOKEN;\n"
            "the page keeps it as a cookie), or --token TOKEN. API clients send `Authorization: Bearer TOKEN`.\n"
            "A --host that is not a loopback address is refused unless --token is given.\n");
        return kOk;
    }
    if (!args.error.empty()) return usageError(args.error, "serve");
    ServeOptions so;
    uint32_t port = 8080, interval = 100;
    if (args.has("port") && (!parseCount(args.get("port"), port, /*allowZero=*/true) || port > 65535))
        return usageError("--port must be a TCP port in 0..65535 (0: any free port)", "serve");
    if (args.has("interval") && !parseCount(args.get("interval"), interval)) return usageError("--interval must be milliseconds", "serve");
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

int cmdExportScene(int argc, char** argv) {
    Args args = Args::parse(argc, argv, 2, {"scene", "out"});
    if (args.help) {
        std::printf("usage: rgraph export-scene --scene SCENE.lua --out FILE.glb\n\n"
                    "Builds a Lua scene (or reads a .gltf/.glb) and writes it as binary glTF: meshes, materials\n"
                    "(metallic-roughness; what glTF cannot say goes to the material's extras), embedded images,\n"
                    "cameras and the lights glTF can express (KHR_lights_punctual: cd, lux).\n");
        return kOk;
    }
    if (!args.error.empty()) return usageError(args.error, "export-scene");
    std::vector<std::string> positional = args.all("");
    std::string scene = args.get("scene", positional.size() > 0 ? positional[0] : "");
    std::string out = args.get("out", positional.size() > 1 ? positional[1] : "");
    if (scene.empty() || out.empty()) return usageError("give --scene SCENE and --out FILE.glb", "export-scene");
    const std::string ext = fs::path(scene).extension().string();
    auto loaded = ext == ".lua" ? loadSceneScript(scene) : loadGltf(scene);
    if (!loaded) return report(loaded.error());
    std::vector<std::string> warnings;
    if (auto r = exportGlb(*loaded, out, &warnings); !r) return report(r.error());
    for (const auto& w : warnings) std::fprintf(stderr, "rgraph: warning: %s\n", w.c_str());
    std::printf("rgraph: wrote %s (%zu meshes, %zu materials, %zu lights, %zu cameras)\n", out.c_str(), loaded->meshes.size(),
                loaded->materials.size(), loaded->lights.size(), loaded->cameras.size());
    return kOk;
}

int cmdBake(int argc, char** argv) {
    Args args = Args::parse(argc, argv, 2, {"scene", "scene-arg", "out", "rebake"});
    if (args.help) {
        std::printf("usage: rgraph bake [--scene FILE.lua] [--scene-arg NAME=VALUE]... [--out FILE.exr] [--rebake]\n\n"
                    "Bakes the scene's spherical-Gaussian lightmap (its scene.lightmap declaration; seed 003) on the CPU:\n"
                    "paths traced with Intel Embree from every texel of the scene's lightmap atlas, the incoming\n"
                    "radiance fitted to N non-negative SG lobes. The result is cached by the scene's content hash in\n"
                    "the cache folder (RG_CACHE_DIR)/lightmaps, where `rgraph render` finds it; a scene or setting that\n"
                    "changes bakes anew. --rebake bakes even when the cache has it; --out also writes the lightmap\n"
                    "EXR there (a layer per lobe: sg0.R ... with the basis in its header).\n");
        return kOk;
    }
    if (!args.error.empty()) return usageError(args.error, "bake");
    const std::string file = args.get("scene", projectRoot() + "/scripts/scenes/default.lua");
    const std::string ext = fs::path(file).extension().string();
    std::map<std::string, std::string> sceneArgs;
    for (const auto& a : args.all("scene-arg")) {
        const auto eq = a.find('=');
        if (eq == std::string::npos || eq == 0) return usageError("--scene-arg must be NAME=VALUE, got '" + a + "'", "bake");
        sceneArgs[a.substr(0, eq)] = a.substr(eq + 1);
    }
    SceneScriptOptions so;
    so.args = sceneArgs;
    so.projectRoot = projectRoot();
    auto scene = ext == ".lua" ? loadSceneScript(file, so) : loadGltf(file);
    if (!scene) return report(scene.error());
    if (!scene->lightmap)
        return report(Error(ErrorCode::InvalidInput, file + ": the scene declares no scene.lightmap (e.g. scene.lightmap \"gi\" { density = 4 })"));
    if (auto r = chooseEnvironment(*scene, "", ext == ".gltf" || ext == ".glb"); !r) return report(r.error());
    bake::PrepareOptions po;
    po.cacheDir = cacheDir() + "/lightmaps";
    po.rebake = args.has("rebake");
    bake::BakeStats stats;
    bool fromCache = false;
    std::string path;
    po.stats = &stats;
    po.fromCache = &fromCache;
    po.path = &path;
    if (auto r = bake::prepareLightmap(*scene, po); !r)
        return report(Error(r.error().code, scene->lightmap->origin + ": scene.lightmap." + scene->lightmap->name + ": " + r.error().message));
    const Lightmap& lm = *scene->bakedLightmap;
    const double mib = double(lm.width) * lm.height * double(lm.axes.size()) * 3 * 4 / (1 << 20);
    const double gpuMib = double(lm.width) * lm.height * double(lm.axes.size() + 1) * 8 / (1 << 20);  // + the flat normal's irradiance
    std::printf("rgraph: lightmap %ux%u, %zu lobes (sharpness %.3f), %.2f texels/m: %.2f MiB as 32-bit floats, %.2f MiB on the GPU (RGBA16F)\n",
                lm.width, lm.height, lm.axes.size(), double(lm.sharpness), double(lm.density), mib, gpuMib);
    if (fromCache)
        std::printf("rgraph: up to date in the cache: %s\n", path.c_str());
    else
        std::printf("rgraph: baked %u texels in %.2f s: %.1f M rays (Embree), %.2f M rays/s; cached as %s\n", stats.texels, stats.seconds,
                    double(stats.rays) * 1e-6, stats.seconds > 0 ? double(stats.rays) / stats.seconds * 1e-6 : 0.0, path.c_str());
    if (args.has("out")) {
        if (auto r = bake::writeLightmapExr(args.get("out"), lm); !r) return report(r.error());
        std::printf("rgraph: wrote %s\n", args.get("out").c_str());
    }
    return kOk;
}

int cmdAccuracy(int argc, char** argv) {
    Args args = Args::parse(argc, argv, 2, {"size", "frames", "samples", "light", "placement", "material", "model", "report"});
    if (args.help) {
        std::printf("usage: rgraph accuracy [--size WxH] [--frames N] [--samples S] [--light L]... [--placement P]... [--material M]... [--model M]...\n"
                    "                       [--report DIR]\n\n"
                    "Renders every area light type (sphere, disk, rect, tube) x placement (facing, grazing, horizon: crossing\n"
                    "the floor's plane) x material (rough, glossy dielectric, glossy metal) of scripts/scenes/accuracy.lua\n"
                    "with the real-time pipeline under each area-light model (frostbite, ltc: the pipeline's area_lights)\n"
                    "and with the reference mode (reference.lua, N frames of S samples (default 4), in\n"
                    "two independent halves), and prints per case the mean and 95th-percentile relative error and the\n"
                    "energy error over the pixels the reference lights above 1 %% of its peak, beside the reference's\n"
                    "own noise (the halves' mean relative difference / 2). --report DIR writes DIR/index.html with a\n"
                    "heat map per case (default out/accuracy). Defaults: 160x120, 64 frames per half, every case.\n");
        return kOk;
    }
    if (!args.error.empty()) return usageError(args.error, "accuracy");
    AccuracyOptions o;
    if (args.has("size") && !parseSize(args.get("size"), o.width, o.height))
        return usageError("--size must be WIDTHxHEIGHT, e.g. 160x120; got '" + args.get("size") + "'", "accuracy");
    if (args.has("frames") && !parseCount(args.get("frames"), o.frames)) return usageError("--frames must be a positive whole number", "accuracy");
    if (args.has("samples") && (!parseCount(args.get("samples"), o.samples) || o.samples > 1024))
        return usageError("--samples must be a whole number from 1 to 1024", "accuracy");
    auto pick = [&](const char* option, std::vector<std::string>& list) -> bool {
        const auto chosen = args.all(option);
        if (chosen.empty()) return true;
        for (const auto& c : chosen)
            if (std::find(list.begin(), list.end(), c) == list.end()) {
                std::string all;
                for (const auto& x : list) all += (all.empty() ? "'" : ", '") + x + "'";
                usageError("--" + std::string(option) + " '" + c + "': expected one of " + all, "accuracy");
                return false;
            }
        list = chosen;
        return true;
    };
    if (!pick("light", o.lights) || !pick("placement", o.placements) || !pick("material", o.materials) || !pick("model", o.models))
        return kUsage;
    auto rt = Runtime::create({});
    if (!rt) return report(rt.error());
    const bool tty = isatty(fileno(stderr));
    o.progress = [tty](const std::string& name, size_t i, size_t n) {
        std::fprintf(stderr, tty ? "\rrgraph: accuracy %zu/%zu: %-28s" : "rgraph: accuracy %zu/%zu: %s\n", i + 1, n, name.c_str());
    };
    auto cases = runAccuracy(**rt, o);
    if (tty) std::fprintf(stderr, "\n");
    if (!cases) return report(cases.error());
    std::printf("%s", accuracyTable(*cases).c_str());
    const std::string dir = args.get("report", "out/accuracy");
    if (auto r = writeAccuracyReport(*cases, dir); !r) return report(r.error());
    std::printf("rgraph: wrote %s/index.html (%ux%u, %u reference frames per half)\n", dir.c_str(), o.width, o.height, o.frames);
    return (*rt)->gpu().validationMessageCount() ? kFailed : kOk;
}

int cmdCompare(int argc, char** argv) {
    using namespace rg::golden;
    Args args = Args::parse(argc, argv, 2, {"layer", "heatmap", "tolerance"});
    if (args.help) {
        std::printf("usage: rgraph compare A.exr B.exr [--layer NAME] [--heatmap FILE.png] [--tolerance T]\n\n"
                    "Compares layer NAME (default 'hdr', else the first layer) of A against B (the reference): mean and\n"
                    "max relative error |a - b| / max(|b|, 1e-3), RMSE and PSNR (peak: B's maximum), over RGB. --heatmap\n"
                    "writes the per-pixel relative error as a colour map (black 0, white >= the max). With --tolerance,\n"
                    "exits 1 when the mean relative error exceeds it.\n");
        return kOk;
    }
    if (!args.error.empty()) return usageError(args.error, "compare");
    const auto files = args.all("");
    if (files.size() != 2) return usageError("give two EXR files: the image and the reference", "compare");
    auto a = readExr(files[0]);
    if (!a) return report(a.error());
    auto b = readExr(files[1]);
    if (!b) return report(b.error());
    auto pick = [&](const ExrFile& f, const std::string& file) -> Result<Image> {
        const std::string want = args.get("layer", "hdr");
        for (const auto& l : f.layers)
            if (l.name == want) return l.image;
        if (!args.has("layer") && !f.layers.empty()) return f.layers.front().image;
        return fail(ErrorCode::NotFound, "'" + file + "' has no layer '" + want + "'");
    };
    auto ia = pick(*a, files[0]);
    if (!ia) return report(ia.error());
    auto ib = pick(*b, files[1]);
    if (!ib) return report(ib.error());
    std::vector<uint32_t> rgb;
    for (uint32_t c = 0; c < std::min(3u, ib->channels); ++c) rgb.push_back(c);
    float peak = 0;
    for (float v : ib->pixels) peak = std::max(peak, v);
    std::map<std::string, MetricResult> results;
    for (Metric m : {Metric::RelMean, Metric::RelMax, Metric::Rmse, Metric::Psnr}) {
        Comparison c;
        c.metric = m;
        c.channels = rgb;
        c.peak = peak > 0 ? peak : 1.0;
        auto r = compare(*ia, *ib, c);
        if (!r) return report(r.error());
        results[metricName(m)] = *r;
    }
    std::printf("rgraph compare: %s vs %s (%ux%u)\n", files[0].c_str(), files[1].c_str(), ib->width, ib->height);
    std::printf("  mean relative error %s\n  max relative error  %s (%s)\n  RMSE                %s\n  PSNR                %s dB\n",
                formatNumber(results["rel_mean"].value).c_str(), formatNumber(results["rel_max"].value).c_str(),
                results["rel_max"].detail.c_str(), formatNumber(results["rmse"].value).c_str(),
                formatNumber(results["psnr"].value).c_str());
    if (args.has("heatmap")) {
        const MetricResult& rel = results["rel_max"];
        Image map = heatMap(rel.error, static_cast<float>(std::max(rel.value, 1e-6)));
        if (auto r = writePng(args.get("heatmap"), map); !r) return report(r.error());
        std::printf("  heat map: %s\n", args.get("heatmap").c_str());
    }
    if (args.has("tolerance")) {
        const double t = std::strtod(args.get("tolerance").c_str(), nullptr);
        if (results["rel_mean"].value > t) {
            std::printf("rgraph compare: mean relative error above the tolerance %s\n", formatNumber(t).c_str());
            return kFailed;
        }
    }
    return kOk;
}

struct Stat {
    double median = 0, min = 0, max = 0;
};
Stat stats(std::vector<double> v) {
    Stat s;
    if (v.empty()) return s;
    std::sort(v.begin(), v.end());
    s.min = v.front();
    s.max = v.back();
    s.median = v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
    return s;
}

int cmdBench(int argc, char** argv) {
    Args args = Args::parse(argc, argv, 2, {"pipeline", "scene", "scene-arg", "set", "camera", "environment", "size", "frames", "json", "device", "floors"});
    if (args.help) {
        std::printf(
            "usage: rgraph bench [--pipeline FILE.lua|builtin:NAME] [--scene FILE] [--scene-arg NAME=VALUE]... [--set NAME=VALUE]...\n"
            "                    [--environment FILE|sky|none] [--size WxH] [--frames N] [--json FILE] [--floors] [--device N]\n\n"
            "--environment FILE|sky|none: replaces the scene's environment (the distant light probe and the sky):\n"
            "an equirectangular .hdr/.exr in nits, the Preetham sky of the scene's sun, or none. A glTF scene\n"
            "with no light and no environment gets the sky, as glTF viewers light published models.\n"
            "--scene-arg NAME=VALUE (repeatable): sets scene.args.NAME for a Lua scene (a number when it reads as one).\n"
            "--set NAME=VALUE (repeatable): sets the pipeline parameter NAME (rg.param) before the first frame.\n"
            "Renders N frames (default 20) at WxH (default 1280x720), one frame at a time, and prints per pass\n"
            "the median/min/max GPU time (timestamp queries), the CPU recording time, the frame total, the\n"
            "graph compile time and the transient memory with and without aliasing. --json writes the same.\n"
            "--floors: then renders the same frames again with every fragment shader replaced by one that writes\n"
            "zeros to the same targets and every compute shader by an empty one (same targets, geometry,\n"
            "state and dispatches), and prints each pass's floor beside its time: what its shaders cost.\n");
        return kOk;
    }
    if (!args.error.empty()) return usageError(args.error, "bench");
    auto setup = setupRun(args, "bench", 20, {});
    if (!setup) return report(setup.error());
    Runtime& rt = *setup->runtime;
    gpu::Executor& ex = rt.executor();
    std::map<std::string, std::vector<double>> perPass, floorPass;
    std::vector<double> totals, records, callbacks, floorTotals;
    std::map<std::string, double> firstFrame;
    // One warm-up frame: the first draw of each pipeline JIT-compiles on lavapipe, and passes of
    // cadence "once" (environment filtering, lookup tables) run only there; its times are the
    // "first" column.
    auto measure = [&](std::map<std::string, std::vector<double>>& passes, std::vector<double>& frameTotals, bool main) -> Result<void> {
        if (auto r = ex.frame(); !r) return r;
        if (auto r = ex.finish(); !r) return r;
        if (main)
            for (const auto& t : ex.lastTimings()) firstFrame[t.name] = t.gpuMs;
        for (uint32_t f = 0; f < setup->frames; ++f) {
            if (auto r = setup->frame(); !r) return r;
            if (auto r = ex.finish(); !r) return r;
            double total = 0;
            for (const auto& t : ex.lastTimings()) {
                passes[t.name].push_back(t.gpuMs);
                total += t.gpuMs;
            }
            frameTotals.push_back(total);
            if (!main) continue;
            records.push_back(ex.lastRecordMs());
            if (setup->session) callbacks.push_back(setup->session->lastFrameCallbackMs());
        }
        return {};
    };
    if (auto r = measure(perPass, totals, true); !r) return report(r.error());
    const bool floors = args.has("floors");
    const gpu::BuildStats mainBuild = ex.buildStats();
    const double loadMs = setup->session ? setup->session->lastLoadMs() : 0.0;
    const double sceneLoadMs = setup->session ? setup->session->lastSceneLoadMs() : 0.0;
    if (floors) {
        if (!setup->session) return report(Error(ErrorCode::Unsupported, "bench --floors: built-in graphs have no floors; give a Lua pipeline"));
        ex.setFloors(true);
        if (auto r = setup->session->load(setup->pipeline); !r) return report(r.error());
        if (auto r = measure(floorPass, floorTotals, false); !r) return report(r.error());
        ex.setFloors(false);
    }
    const Plan& plan = ex.plan();
    uint32_t w = plan.outputWidth, h = plan.outputHeight;
    std::printf("rgraph bench: %s, %ux%u, %u frames, %s\n", setup->pipeline.c_str(), w, h,
                setup->frames, rt.gpu().deviceInfo().name.c_str());
    if (floors) std::printf("%-24s %10s %10s %10s %10s %10s\n", "pass (GPU ms)", "median", "min", "max", "first", "floor");
    else std::printf("%-24s %10s %10s %10s %10s\n", "pass (GPU ms)", "median", "min", "max", "first");
    nlohmann::json j;
    j["pipeline"] = setup->pipeline;
    j["size"] = {w, h};
    j["frames"] = setup->frames;
    j["device"] = rt.gpu().deviceInfo().name;
    for (const auto& p : plan.passes) {
        Stat s = stats(perPass[p.name]);
        nlohmann::json pj = {{"name", p.name}, {"kind", p.kind}, {"medianMs", s.median}, {"minMs", s.min}, {"maxMs", s.max},
                             {"firstMs", firstFrame[p.name]}};
        if (floors) {
            const Stat fl = stats(floorPass[p.name]);
            std::printf("%-24s %10.3f %10.3f %10.3f %10.3f %10.3f\n", p.name.c_str(), s.median, s.min, s.max, firstFrame[p.name], fl.median);
            pj["floorMs"] = fl.median;
        } else
            std::printf("%-24s %10.3f %10.3f %10.3f %10.3f\n", p.name.c_str(), s.median, s.min, s.max, firstFrame[p.name]);
        j["passes"].push_back(pj);
    }
    Stat t = stats(totals), rec = stats(records);
    if (floors) {
        const Stat ft = stats(floorTotals);
        std::printf("%-24s %10.3f %10.3f %10.3f %10s %10.3f\n", "frame total", t.median, t.min, t.max, "", ft.median);
        j["floorTotalMs"] = ft.median;
    } else
        std::printf("%-24s %10.3f %10.3f %10.3f\n", "frame total", t.median, t.min, t.max);
    std::printf("%-24s %10.3f %10.3f %10.3f\n", "CPU recording", rec.median, rec.min, rec.max);
    if (setup->session) {
        Stat cb = stats(callbacks);
        std::printf("%-24s %10.3f %10.3f %10.3f\n", "rg.frame (Lua)", cb.median, cb.min, cb.max);
        std::printf("pipeline load %.1f ms (script, shaders, graph compile, resources, pipelines)\n", loadMs);
        if (const passes::GpuScene* scene = setup->session->gpuScene()) {
            uint64_t triangles = 0;
            for (const auto& d : scene->draws()) triangles += d.indexCount / 3;
            std::printf("scene: %zu draws, %llu triangles, %zu materials, %u lights; loaded in %.1f ms (read, build, upload)\n",
                        scene->draws().size(), static_cast<unsigned long long>(triangles), scene->scene().materials.size(),
                        scene->lightCount(), sceneLoadMs);
            j["scene"] = {{"draws", scene->draws().size()}, {"triangles", triangles}, {"lights", scene->lightCount()},
                          {"loadMs", sceneLoadMs}};
        }
        j["luaFrameMs"] = {{"median", cb.median}, {"min", cb.min}, {"max", cb.max}};
        j["loadMs"] = loadMs;
    }
    const auto& bs = mainBuild;
    std::printf("graph compile %.3f ms, resources %.3f ms, pass setup %.3f ms\n", bs.compileMs, bs.resourcesMs, bs.prepareMs);
    std::printf("transient memory: %.2f MiB aliased, %.2f MiB without aliasing\n",
                static_cast<double>(plan.transientBytesAliased) / (1 << 20),
                static_cast<double>(plan.transientBytesUnaliased) / (1 << 20));
    j["frameTotalMs"] = {{"median", t.median}, {"min", t.min}, {"max", t.max}};
    j["cpuRecordMs"] = {{"median", rec.median}, {"min", rec.min}, {"max", rec.max}};
    j["compileMs"] = bs.compileMs;
    j["transientBytesAliased"] = plan.transientBytesAliased;
    j["transientBytesUnaliased"] = plan.transientBytesUnaliased;
    if (args.has("json")) {
        std::ofstream f(args.get("json"));
        if (!f) return report(Error(ErrorCode::Io, "cannot write '" + args.get("json") + "'"));
        f << j.dump(2) << "\n";
    }
    return rt.gpu().validationMessageCount() ? kFailed : kOk;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2 || !std::strcmp(argv[1], "--help") || !std::strcmp(argv[1], "-h") || !std::strcmp(argv[1], "help")) {
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
    if (cmd == "test") return goldenCommand(argc, argv);
    if (cmd == "compare") return cmdCompare(argc, argv);
    std::fprintf(stderr, "rgraph: unknown command '%s'\n\n%s", cmd.c_str(), kMainHelp);
    return kUsage;
}

// The command line's shared pieces: exit codes and error reports, the argument reader, the
// pipeline a command works on, the render set-up shared by render, bench, watch and serve, the
// EXR/PNG outputs; and one function per command (cmd_*.cpp), which main.cpp dispatches to.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/compiler.h"
#include "image/image.h"
#include "runtime/runtime.h"
#include "runtime/session.h"

// Help lines several commands share, as string-literal macros so that each command's help stays
// one literal.
#define RG_HELP_ENVIRONMENT                                                                    \
    "--environment FILE|sky|none: replaces the scene's environment (the distant light probe "  \
    "and the sky):\n"                                                                          \
    "an equirectangular .hdr/.exr in nits, the Preetham sky of the scene's sun, or none. A "   \
    "glTF scene\n"                                                                             \
    "with no light and no environment gets the sky, as glTF viewers light published models.\n" \
    "--variant NAME: a glTF scene's material variant (KHR_materials_variants).\n"              \
    "--environment-sun auto|light|remove|keep: what becomes of a sun in an .hdr/.exr "         \
    "environment\n(scripts/scenes/README.md, scene.environment's sun; default: the scene's, "  \
    "else auto).\n"
#define RG_HELP_SCENE_ARGS_AND_SET                                                              \
    "--scene-arg NAME=VALUE (repeatable): sets scene.args.NAME for a Lua scene (a number when " \
    "it reads as one).\n"                                                                       \
    "--set NAME=VALUE (repeatable): sets the pipeline parameter NAME (rg.param) before the "    \
    "first frame.\n"

namespace rg::cli {

namespace fs = std::filesystem;

// Exit codes: 0 success, 1 a failed check or a device failure, 2 bad usage or bad input.
constexpr int kOk = 0, kFailed = 1, kUsage = 2;

int exitCodeOf(const Error& e);
int report(const Error& e);  // prints "rgraph: error: ..." and returns the exit code
int usageError(const std::string& msg, const char* command);

// A tiny argument reader: --flag VALUE, --flag=VALUE, repeated flags, --help.
struct Args {
    std::map<std::string, std::vector<std::string>> values;
    bool help = false;
    std::string error;

    static Args parse(int argc, char** argv, int first, const std::vector<std::string>& known);
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

// A command's options from argv[2...] into `args`: with --help it prints `help` and returns kOk;
// an unknown option or a missing value returns the usage error; otherwise nothing (go on).
std::optional<int> parseCommand(int argc, char** argv, const char* command,
                                const std::vector<std::string>& options, const char* help,
                                Args& args);

bool parseSize(const std::string& s, uint32_t& w, uint32_t& h);
bool parseCount(const std::string& s, uint32_t& n, bool allowZero = false);
// "K/N" with 1 <= K <= N <= 65536, as a 0-based shard of N.
bool parseShard(const std::string& s, uint32_t& shard, uint32_t& shards);

std::string defaultPipeline();
std::string pipelineArg(const Args& args);
bool isBuiltin(const std::string& p);
// The graph a command works on, without a GPU: a pipeline script or builtin:NAME.
Result<GraphDesc> loadGraph(const Args& args);

struct RenderSetup {
    std::unique_ptr<Runtime> runtime;
    std::unique_ptr<Session> session;  // null for builtin:NAME graphs
    uint32_t frames = 1;               // to run, warm-up included
    // --frames A..B (render): the frames run are numbered from firstFrame = A - warm-up, and
    // those from rangeStart = A on are each written (framePath).
    bool range = false;
    uint64_t firstFrame = 0, rangeStart = 0;
    std::string pipeline;
    double deviceMs = 0.0;  // Vulkan instance and device

    uint64_t framesRun = 0;
    Result<void> frame() {
        ++framesRun;
        return session ? session->frame() : runtime->executor().frame();
    }
    uint64_t lastFrameNumber() const { return firstFrame + framesRun - 1; }
    std::string output() const { return session ? session->pipeline().output : "output"; }
};

// Shared by render, bench and watch: options, runtime, pipeline load and build.
Result<RenderSetup> setupRun(const Args& args, const char* command, uint32_t defaultFrames,
                             const std::vector<std::string>& captures, bool verbose = false);
// A file as the outputs name it: relative to the project root when inside it
// ("scripts/pipelines/deferred.lua"), else its file name — never a machine path.
std::string logicalName(const std::string& path);
std::string exrMetaDevice(Runtime& rt);
std::vector<std::string> rgbaNames(uint32_t n);
std::string number(double v);
// Writes the EXR (linear: layer `hdr` in cd/m² when the pipeline has a physical camera, plus one
// layer per capture) and the PNG (the display image). Returns the display image.
Result<Image> writeOutputs(RenderSetup& setup, const std::string& exrPath,
                           const std::string& pngPath, const std::vector<std::string>& captures);
// Frame `frame`'s file of a sequence: a run of '#' in the file name replaced by the number,
// zero-padded to the run's length ("shot.####.exr"), else ".NNNN" before the extension.
std::string framePath(const std::string& path, uint64_t frame);
// The EXR and PNG paths a command writes (--out, --png).
Result<std::pair<std::string, std::string>> outputPaths(const Args& args,
                                                        const std::string& defaultExr);

int cmdDevices(int argc, char** argv);
int cmdGraph(int argc, char** argv);
int cmdRender(int argc, char** argv);
int cmdWatch(int argc, char** argv);
int cmdServe(int argc, char** argv);
int cmdExportScene(int argc, char** argv);
int cmdBake(int argc, char** argv);
int cmdAccuracy(int argc, char** argv);
int cmdCompare(int argc, char** argv);
int cmdBench(int argc, char** argv);
int cmdGallery(int argc, char** argv);

}  // namespace rg::cli

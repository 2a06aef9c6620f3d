// `rgraph bench`: every pass timed over several frames.
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

#include <nlohmann/json.hpp>
#include "cli.h"

namespace rg::cli {

namespace {

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

const char* const kHelp =
    "usage: rgraph bench [--pipeline FILE.lua|builtin:NAME] [--scene FILE] [--scene-arg "
    "NAME=VALUE]... [--set NAME=VALUE]...\n"
    "                    [--environment FILE|sky|none] [--size WxH] [--frames N] [--json FILE] "
    "[--floors] [--device N]\n\n" RG_HELP_ENVIRONMENT RG_HELP_SCENE_ARGS_AND_SET
    "Renders N frames (default 20) at WxH (default 1280x720), one frame at a time, and prints per "
    "pass\n"
    "the median/min/max GPU time (timestamp queries), the CPU recording time, the frame total "
    "(the\n"
    "passes' sum) beside the frame's wall time (its rg.frame to its fence), the graph compile time "
    "and\n"
    "the transient memory with and without aliasing. --json writes the same.\n"
    "--floors: then renders the same frames again with every fragment shader replaced by one that "
    "writes\n"
    "zeros to the same targets and every compute shader by an empty one (same targets, geometry,\n"
    "state and dispatches), and prints each pass's floor beside its time: what its shaders cost.\n";

}  // namespace

int cmdBench(int argc, char** argv) {
    Args args;
    if (auto done = parseCommand(
            argc, argv, "bench",
            {"pipeline", "scene", "scene-arg", "set", "camera", "environment", "environment-sun",
             "variant", "size", "frames", "json", "device", "floors"},
            kHelp, args))
        return *done;
    auto setup = setupRun(args, "bench", 20, {});
    if (!setup) return report(setup.error());
    Runtime& rt = *setup->runtime;
    gpu::Executor& ex = rt.executor();
    std::map<std::string, std::vector<double>> perPass, floorPass, perPassCpu;
    std::vector<double> totals, records, sceneUpdates, callbacks, floorTotals, walls;
    std::map<std::string, double> firstFrame;
    // One warm-up frame: the first draw of each pipeline JIT-compiles on lavapipe, and passes of
    // cadence "once" (environment filtering, lookup tables) run only there; its times are the
    // "first" column.
    auto measure = [&](std::map<std::string, std::vector<double>>& passes,
                       std::vector<double>& frameTotals, bool main) -> Result<void> {
        if (auto r = ex.frame(); !r) return r;
        if (auto r = ex.finish(); !r) return r;
        if (main)
            for (const auto& t : ex.lastTimings()) firstFrame[t.name] = t.gpuMs;
        for (uint32_t f = 0; f < setup->frames; ++f) {
            const auto start = std::chrono::steady_clock::now();
            if (auto r = setup->frame(); !r) return r;
            if (auto r = ex.finish(); !r) return r;
            // The frame as a clock on the wall sees it, from its rg.frame to its fence: what the
            // timestamps' sum must come near (their gaps, barriers and waits are in it too).
            if (main)
                walls.push_back(std::chrono::duration<double, std::milli>(
                                    std::chrono::steady_clock::now() - start)
                                    .count());
            double total = 0;
            for (const auto& t : ex.lastTimings()) {
                passes[t.name].push_back(t.gpuMs);
                total += t.gpuMs;
            }
            frameTotals.push_back(total);
            if (!main) continue;
            for (const auto& t : ex.lastTimings()) perPassCpu[t.name].push_back(t.cpuMs);
            records.push_back(ex.lastRecordMs());
            sceneUpdates.push_back(ex.lastSceneUpdateMs());
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
        if (!setup->session)
            return report(
                Error(ErrorCode::Unsupported,
                      "bench --floors: built-in graphs have no floors; give a Lua pipeline"));
        ex.setFloors(true);
        if (auto r = setup->session->load(setup->pipeline); !r) return report(r.error());
        if (auto r = measure(floorPass, floorTotals, false); !r) return report(r.error());
        ex.setFloors(false);
    }
    const Plan& plan = ex.plan();
    uint32_t w = plan.outputWidth, h = plan.outputHeight;
    std::printf("rgraph bench: %s, %ux%u, %u frames, %s\n", setup->pipeline.c_str(), w, h,
                setup->frames, rt.gpu().deviceInfo().name.c_str());
    if (floors)
        std::printf("%-24s %10s %10s %10s %10s %10s\n", "pass (GPU ms)", "median", "min", "max",
                    "first", "floor");
    else
        std::printf("%-24s %10s %10s %10s %10s\n", "pass (GPU ms)", "median", "min", "max",
                    "first");
    nlohmann::json j;
    j["pipeline"] = setup->pipeline;
    j["size"] = {w, h};
    j["frames"] = setup->frames;
    j["device"] = rt.gpu().deviceInfo().name;
    for (const auto& p : plan.passes) {
        Stat s = stats(perPass[p.name]);
        nlohmann::json pj = {{"name", p.name},
                             {"kind", p.kind},
                             {"medianMs", s.median},
                             {"minMs", s.min},
                             {"maxMs", s.max},
                             {"firstMs", firstFrame[p.name]},
                             {"cpuMedianMs", stats(perPassCpu[p.name]).median}};
        if (floors) {
            const Stat fl = stats(floorPass[p.name]);
            std::printf("%-24s %10.3f %10.3f %10.3f %10.3f %10.3f\n", p.name.c_str(), s.median,
                        s.min, s.max, firstFrame[p.name], fl.median);
            pj["floorMs"] = fl.median;
        } else
            std::printf("%-24s %10.3f %10.3f %10.3f %10.3f\n", p.name.c_str(), s.median, s.min,
                        s.max, firstFrame[p.name]);
        j["passes"].push_back(pj);
    }
    Stat t = stats(totals), rec = stats(records);
    if (floors) {
        const Stat ft = stats(floorTotals);
        std::printf("%-24s %10.3f %10.3f %10.3f %10s %10.3f\n", "frame total", t.median, t.min,
                    t.max, "", ft.median);
        j["floorTotalMs"] = ft.median;
    } else
        std::printf("%-24s %10.3f %10.3f %10.3f\n", "frame total", t.median, t.min, t.max);
    const Stat wall = stats(walls);
    std::printf("%-24s %10.3f %10.3f %10.3f\n", "frame wall time", wall.median, wall.min, wall.max);
    std::printf("%-24s %10.3f %10.3f %10.3f\n", "CPU recording", rec.median, rec.min, rec.max);
    // Where the recording's CPU time goes: the scene's update (camera, moving nodes, shadow views)
    // and the passes that record the most (the CPU path's camera culling and levels among them).
    const Stat update = stats(sceneUpdates);
    std::vector<std::pair<double, std::string>> cpuPasses;
    for (const auto& [name, ms] : perPassCpu) cpuPasses.emplace_back(stats(ms).median, name);
    std::sort(cpuPasses.rbegin(), cpuPasses.rend());
    std::string top;
    for (size_t i = 0; i < std::min<size_t>(cpuPasses.size(), 4); ++i)
        top += (i ? ", " : "") + cpuPasses[i].second + " " +
               std::to_string(cpuPasses[i].first).substr(0, 5);
    std::printf("  of which scene update %.3f ms; most recording: %s\n", update.median,
                top.c_str());
    j["sceneUpdateMs"] = update.median;
    if (setup->session) {
        Stat cb = stats(callbacks);
        std::printf("%-24s %10.3f %10.3f %10.3f\n", "rg.frame (Lua)", cb.median, cb.min, cb.max);
        std::printf(
            "pipeline load %.1f ms (script, shaders, graph compile, resources, pipelines)\n",
            loadMs);
        if (const passes::GpuScene* scene = setup->session->gpuScene()) {
            uint64_t triangles = 0;
            for (const auto& d : scene->draws()) triangles += d.indexCount / 3;
            std::printf(
                "scene: %zu draws, %llu triangles, %zu materials, %u lights; loaded in %.1f ms "
                "(read, build, upload)\n",
                scene->draws().size(), static_cast<unsigned long long>(triangles),
                scene->scene().materials.size(), scene->lightCount(), sceneLoadMs);
            const passes::GpuScene::Memory mem = scene->memory();
            const auto mib = [](uint64_t b) { return static_cast<double>(b) / (1 << 20); };
            std::printf(
                "scene memory: geometry %.2f MiB, textures %.2f MiB, environment %.2f MiB, "
                "lightmap %.2f MiB\n",
                mib(mem.geometry), mib(mem.textures), mib(mem.environment), mib(mem.lightmap));
            j["scene"] = {{"draws", scene->draws().size()},      {"triangles", triangles},
                          {"lights", scene->lightCount()},       {"loadMs", sceneLoadMs},
                          {"geometryBytes", mem.geometry},       {"textureBytes", mem.textures},
                          {"environmentBytes", mem.environment}, {"lightmapBytes", mem.lightmap}};
        }
        j["luaFrameMs"] = {{"median", cb.median}, {"min", cb.min}, {"max", cb.max}};
        j["loadMs"] = loadMs;
    }
    const auto& bs = mainBuild;
    std::printf("graph compile %.3f ms, resources %.3f ms, pass setup %.3f ms\n", bs.compileMs,
                bs.resourcesMs, bs.prepareMs);
    std::printf("transient memory: %.2f MiB aliased, %.2f MiB without aliasing\n",
                static_cast<double>(plan.transientBytesAliased) / (1 << 20),
                static_cast<double>(plan.transientBytesUnaliased) / (1 << 20));
    j["frameTotalMs"] = {{"median", t.median}, {"min", t.min}, {"max", t.max}};
    j["frameWallMs"] = {{"median", wall.median}, {"min", wall.min}, {"max", wall.max}};
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

}  // namespace rg::cli

// A golden test as its script declares it (tests/golden/NAME.lua), validated into plain data.
//
// A golden test script returns one table:
//
//   return {
//       doc = "what it shows",                         -- optional, shown in the report
//       pipeline = "scripts/pipelines/test.lua",        -- required; relative to the project root
//       scene = "scripts/scenes/default.lua",           -- optional: .lua, .gltf or .glb, for the
//       camera = "main",                                --   pipeline's scene passes (Session's scene)
//       size = { 64, 64 },                              -- required; at most 256 x 256
//       frames = 3,                                     -- default 1
//       params = { scale = 0.5 },                       -- parameter values before the first frame
//       frame = function(ctx) ... end,                  -- optional; after the pipeline's rg.frame
//       golden = "other_test",                          -- optional: compare with another test's goldens
//       captures = {                                    -- required: resource -> comparison(s)
//           output = { metric = "psnr", tolerance = 50 },
//           pattern = { { metric = "max_abs", tolerance = 0 }, { metric = "flip", tolerance = 0.01 } },
//       },
//       cross_device = {                                -- optional: captures -> comparison(s) that
//           output = { metric = "flip", tolerance = 0.05 }, -- any device family must meet against
//       },                                              --   the primary family's goldens
//   }
//
// Comparison fields: metric (required), tolerance (required except for `exact`, default 0),
// channels ("rgb", "a", ...), threshold (over_threshold, required), epsilon (rel_mean, rel_max),
// peak (psnr), encoding ("signed", "unorm", "oct", "oct_unorm"; angular), display ("linear",
// "srgb"; flip) and ppd (pixels per degree; flip). A field a metric does not use is an error.
//
// This header and golden_test.cpp know no Lua: wrap_golden_test.cpp runs the script and hands
// its table over as an rg::Value.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/result.h"
#include "core/value.h"
#include "golden/metrics.h"
#include "lua/lua_host.h"

namespace rg::golden {

inline constexpr uint32_t kMaxGoldenSize = 256;  // DESIGN §7: goldens stay small
inline constexpr uint32_t kMaxFrames = 1000;

struct CaptureSpec {
    std::string resource;
    std::vector<Comparison> comparisons;
};

struct GoldenTest {
    std::string name;  // the script's file name without .lua
    std::string file;  // the script as given
    std::string doc;
    std::string pipeline;  // as written in the script
    std::string scene, camera;
    uint32_t width = 0, height = 0;
    uint32_t frames = 1;
    std::map<std::string, Value> params;
    bool hasFrameCallback = false;
    std::string golden;  // whose golden images: this test's name unless `golden` is set
    std::vector<CaptureSpec> captures;  // by resource name
    // The bound every device family's run meets against the primary family's goldens
    // (golden/golden_set.h); each names one of `captures`.
    std::vector<CaptureSpec> crossDevice;
};

// Validates the table a golden test script returned. `where` prefixes every error
// ("tests/golden/x.lua"), followed by the field path: "tests/golden/x.lua: captures.output.metric:
// unknown metric 'psnrr' (did you mean 'psnr'?); expected one of: 'max_abs', ...". A `frame` field
// is given as hasFrame (functions are not Values).
Result<GoldenTest> parseGoldenTest(const Value& table, bool hasFrame, const std::string& name,
                                   const std::string& where);

// The golden test scripts (*.lua) directly in `dir` whose name matches `pattern`, sorted.
// Errors: the folder does not exist (NotFound).
Result<std::vector<std::string>> findGoldenTests(const std::string& dir,
                                                 const std::string& pattern);

// True when `name` matches `pattern`: an fnmatch glob ("deferred_*"); without wildcards, the
// name itself. An empty pattern matches every name.
bool matchesPattern(const std::string& name, const std::string& pattern);

// Parses a channel list: letters of "rgba" ("rgb", "a", "rg") into indices.
Result<std::vector<uint32_t>> parseChannels(const std::string& letters);

// A loaded golden test script: its declaration and the Lua state that keeps its `frame`
// function. One thread per script. Implemented in wrap_golden_test.cpp.
class GoldenScript {
public:
    struct Limits {
        uint64_t instructions = 10'000'000;  // per call into the script
        size_t memoryBytes = 64u << 20;
    };
    // Runs the script in a sandbox (base, string, table, math, utf8; no io, os, load, require)
    // and validates what it returned. `chunkName` is how errors name the file (the path
    // relative to the project root when it is inside it).
    static Result<std::unique_ptr<GoldenScript>> load(const std::string& file,
                                                      const std::string& chunkName,
                                                      const Limits& limits);
    static Result<std::unique_ptr<GoldenScript>> load(const std::string& file,
                                                      const std::string& chunkName) {
        return load(file, chunkName, Limits{});
    }
    ~GoldenScript();
    GoldenScript(const GoldenScript&) = delete;
    GoldenScript& operator=(const GoldenScript&) = delete;

    const GoldenTest& test() const { return m_test; }
    // Calls the test's frame(ctx): ctx.frame, ctx.time, ctx.params.NAME (read and set, type- and
    // range-checked), ctx.pass("name").enabled / .shader — the rg.frame interface. `current` holds
    // the pipeline after its own rg.frame ran for this frame. No frame function: no changes.
    Result<FrameChanges> frame(const FrameContext& ctx, const PipelineDesc& current);

    struct Impl;

private:
    GoldenScript();
    std::unique_ptr<Impl> m;
    GoldenTest m_test;
};

}  // namespace rg::golden

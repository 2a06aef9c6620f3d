// The golden test runner: finds golden test scripts, renders each through its pipeline with
// rg::Session on a runtime of its own (nothing carries over between tests), reads back the
// captured resources after the last frame and compares them with the golden images
// (tests/golden/images/<test>/<resource>.exr|png, beside golden.json which records the device,
// the driver, the Mesa version and the determinism profile they were made with).
//
// Determinism profile, applied to every test: LP_NUM_THREADS pinned (2 unless the environment
// sets it; lavapipe's output does not depend on it, its timing does), a fixed frame time
// (ctx.time = frame / 60 s, and a pipeline parameter `frame_time` set to 1/60), and the
// parameters named `dither`, `dithering`, `jitter` and `taa_jitter` switched off; parameters the
// test sets itself are left as it sets them.
//
// Captures are textures (read back as the executor decodes them) or buffers (read as arrays of
// 32-bit floats: one row, one channel, format "buffer:float32").
//
// A failure writes, under the output folder, <test>/<resource>.actual.<ext>,
// .expected.<ext> (EXR captures also as .png previews) and <resource>.<metric>.diff.png, states
// every metric against its tolerance, and names the first capture in pipeline order (the order
// of the passes that last write them) that failed: the resource where the divergence starts.
//
// Session takes the test's parameters and frame callback through SessionOptions::params and
// ::frameHook, and the baker through ::bakeLightmap (a scene's lightmap is baked on first use).
//
// --update blesses: it writes the golden of every capture that has none or no longer passes
// its comparisons, keeps goldens that still pass (so 1-LSB noise never churns the repository),
// removes golden files no capture names, and says which of these it did.
#pragma once

#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "core/result.h"
#include "golden/report.h"

namespace rg::golden {

struct RunnerOptions {
    std::string pattern;                // a test name or a glob ("deferred_*"); empty = every test
    std::string testDir;                // default <project>/tests/golden
    std::string imageDir;               // default <project>/tests/golden/images
    std::string outDir = "out/golden";  // failure artefacts
    std::string reportDir;              // write DIR/index.html when set
    std::string junitFile;              // write JUnit XML when set
    bool update = false;
    bool verbose = false;  // print each rebuild of the session
    // --shard K/N: the tests (matched by the pattern, sorted by name) whose position is K − 1
    // modulo N, so that N shards run each test exactly once. 1/1 = every test.
    uint32_t shard = 1, shards = 1;
    std::optional<uint32_t> device;
};

// Runs the tests and prints progress to `out`. Errors only for what stops every test (no test
// matches, no device); each test's own failures and errors are in the report.
Result<RunReport> runGoldenTests(const RunnerOptions& options, std::FILE* out);

}  // namespace rg::golden

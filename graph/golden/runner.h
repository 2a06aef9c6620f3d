// The golden test runner: finds golden test scripts, renders each through its pipeline on a
// fresh executor, reads back the captured resources and compares them with the golden images
// (tests/golden/images/<test>/<resource>.exr|png, beside golden.json which records the device,
// the driver, the Mesa version and the determinism profile they were made with).
//
// Determinism profile, applied to every test: LP_NUM_THREADS pinned (2 unless the environment
// sets it; lavapipe's output does not depend on it, its timing does), a fixed frame time
// (ctx.time = frame / 60 s), and the parameters named `dither`, `dithering`, `jitter` and
// `taa_jitter` switched off when a pipeline declares them and the test does not set them.
//
// A failure writes, under the output folder, <test>/<resource>.actual.<ext>,
// .expected.<ext> (EXR captures also as .png previews) and <resource>.<metric>.diff.png, states
// every metric against its tolerance, and names the first capture in pipeline order (the order
// of the passes that last write them) that failed: the resource where the divergence starts.
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
    std::string pattern;    // a test name or a glob ("deferred_*"); empty = every test
    std::string testDir;    // default <project>/tests/golden
    std::string imageDir;   // default <project>/tests/golden/images
    std::string outDir = "out/golden";  // failure artefacts
    std::string reportDir;  // write DIR/index.html when set
    std::string junitFile;  // write JUnit XML when set
    bool update = false;
    bool verbose = false;   // print each rebuild of the session
    std::optional<uint32_t> device;
};

// The golden test scripts (*.lua) directly in `dir` whose name matches `pattern`, sorted.
// Errors: the folder does not exist (NotFound).
Result<std::vector<std::string>> findGoldenTests(const std::string& dir, const std::string& pattern);

// True when `name` matches `pattern`: fnmatch glob; a pattern without wildcards is a name.
bool matchesPattern(const std::string& name, const std::string& pattern);

// Runs the tests and prints progress to `out`. Errors only for what stops every test (no test
// matches, no device); each test's own failures and errors are in the report.
Result<RunReport> runGoldenTests(const RunnerOptions& options, std::FILE* out);

// Which storage a resource format's golden uses (by script format name, e.g. "rgba16f").
Storage storageForFormat(const std::string& format);

// The image as its golden stores it: 8-bit rounding for PNG (through sRGB for "rgba8_srgb"),
// binary16 rounding for half EXR, unchanged for float EXR. Comparisons run on this.
Image quantizeForStorage(const Image& image, Storage storage, bool srgb);

}  // namespace rg::golden

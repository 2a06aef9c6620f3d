// What a golden test run found, and the two files it can be written as: a static HTML report
// (one self-contained page, works offline) and JUnit XML. Pure C++: no Vulkan, no Lua.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/result.h"
#include "golden/metrics.h"
#include "image/image.h"

namespace rg::golden {

// How a golden image is stored: losslessly for the resource's format.
enum class Storage : uint8_t {
    Png,       // 8-bit unorm formats (r8, rg8, rgba8, rgba8_srgb: sRGB-encoded in the file)
    ExrHalf,   // half-float formats (r16f, rg16f, rgba16f, r11g11b10f): compressed half EXR
    ExrFloat,  // everything else (32-bit floats, integers, rgb10a2, depth): compressed float EXR
};
const char* storageName(Storage s);       // "png", "exr-half", "exr-float"
const char* storageExtension(Storage s);  // ".png", ".exr"

struct ComparisonOutcome {
    Comparison spec;
    MetricResult result;   // meaningful when error is empty
    std::string error;     // why the comparison could not run (e.g. the golden has another size)
    std::string diffFile;  // heat map written for a failure ("" if none)
    bool passed() const { return error.empty() && result.passed; }
};

struct CaptureOutcome {
    std::string resource;
    std::string format;  // "rgba16f"
    Storage storage = Storage::ExrHalf;
    bool display = false;  // values are display-encoded (shown as they are, no exposure)
    std::string
        writerPass;  // the passes that write it in the plan, in execution order ("a, then b"; "" when none)
    int32_t order =
        -1;  // the first of them's index in the plan: pipeline order (where a difference can start)
    Image actual;              // quantised to the golden's storage
    Image expected;            // empty (0 x 0) when there is no golden image
    std::string expectedFile;  // the golden image's path
    std::string note;          // e.g. "no golden image", "updated: max_abs 0.25 > 0.002"
    std::vector<ComparisonOutcome> comparisons;
    std::vector<std::string> files;  // artefacts written for a failure
    bool passed = false;
};

enum class TestStatus : uint8_t {
    Passed,
    Failed,  // a comparison failed or a golden image is missing
    Error,   // the test could not run: bad script, pipeline error, device failure
};
const char* testStatusName(TestStatus s);  // "PASS", "FAIL", "ERROR"

struct TestOutcome {
    std::string name;
    std::string file;  // the script, relative to the project root where possible
    std::string doc;
    std::string pipeline;
    std::string golden;  // whose golden images it compared with
    uint32_t width = 0, height = 0, frames = 0;
    TestStatus status = TestStatus::Error;
    std::string message;    // the error, or what failed, in one line
    bool badInput = false;  // Error caused by input (script, pipeline, parameters): exit code 2
    std::string firstDivergent;  // the first capture in pipeline order that failed ("" if none)
    std::vector<CaptureOutcome> captures;  // in pipeline order
    std::vector<std::string> changes;      // --update: what it wrote or removed
    std::vector<std::string> log;          // the session's log (rebuilds)
    double seconds = 0.0;
};

// Where the run happened: what the goldens record beside themselves.
struct RunEnvironment {
    std::string family;  // the device family its goldens are kept under (golden/golden_set.h)
    std::string device;  // "llvmpipe (LLVM 15.0.6, 256 bits)"
    std::string driver;  // "llvmpipe Mesa 22.3.6 (LLVM 15.0.6)"
    std::string mesa;    // "22.3.6" ("" when the driver is not Mesa)
    std::string cpu;     // model name from /proc/cpuinfo
    std::string
        cpuFeatures;  // the SIMD features that change lavapipe's code: "sse4_1 avx avx2 fma f16c"
    std::string lpNumThreads;  // LP_NUM_THREADS as the run used it
    std::string vectorWidth;   // LP_NATIVE_VECTOR_WIDTH when set
};

struct RunReport {
    std::vector<TestOutcome> tests;
    RunEnvironment environment;
    std::string profile;  // the determinism profile in one line
    double seconds = 0.0;
    bool update = false;
    size_t count(TestStatus s) const;
};

// Writes DIR/index.html: every test with its status and metrics; for each comparison the
// expected and actual images side by side, a swipe view (a slider divides the two), the diff
// heat map, and an exposure slider for linear (HDR) images. The images are embedded (half
// floats in base64), so the page is one file and needs no network. Query parameters:
// ?swipe=0.3 (every swipe slider), ?exposure=-2 (EV), ?test=NAME (only that test), ?failed=1.
Result<void> writeHtmlReport(const std::string& dir, const RunReport& run);

// Writes a JUnit XML file (one testsuite "golden", one testcase per test).
Result<void> writeJunit(const std::string& file, const RunReport& run);

std::string base64Encode(const uint8_t* data, size_t size);
std::string htmlEscape(const std::string& s);

}  // namespace rg::golden

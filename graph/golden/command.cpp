#include "golden/command.h"

#include <cstdio>
#include <cstring>
#include <string>

#include "golden/runner.h"

namespace rg {

namespace {

constexpr int kOk = 0, kFailed = 1, kUsage = 2;

const char* kHelp =
    "usage: rgraph test [PATTERN] [--update] [--report DIR] [--junit FILE]\n"
    "                   [--dir DIR] [--images DIR] [--out DIR] [--device N] [--shard K/N] "
    "[--verbose]\n"
    "\n"
    "Runs the golden-image tests: each tests/golden/NAME.lua renders a pipeline at a small size "
    "for\n"
    "some frames, captures resources (the output and any intermediate) and compares each with its\n"
    "golden image in tests/golden/images/NAME/ by the metric and tolerance the test states.\n"
    "PATTERN is a test name or a glob ('deferred_*'); default: every test.\n"
    "\n"
    "  --update        bless: write the goldens that are missing or no longer pass (HDR as half "
    "EXR,\n"
    "                  display images as PNG), keep those that still pass, and print what changed\n"
    "  --report DIR    write DIR/index.html: every test, its metrics, expected | actual | swipe | "
    "diff,\n"
    "                  an exposure slider for HDR images (one static page, works offline)\n"
    "  --junit FILE    write JUnit XML\n"
    "  --dir DIR       where the test scripts are (default tests/golden)\n"
    "  --images DIR    where the goldens are (default tests/golden/images)\n"
    "  --out DIR       where a failure writes actual, expected and diff images (default "
    "out/golden)\n"
    "  --device N      the Vulkan device (see 'rgraph devices')\n"
    "  --shard K/N     run shard K of N: the matched tests sorted by name, every N-th from the "
    "K-th,\n"
    "                  so that N shards run each test exactly once (on N machines or "
    "processes)\n"
    "  --verbose       print every rebuild a frame callback causes\n"
    "\n"
    "Determinism profile (recorded in each golden.json): LP_NUM_THREADS=2 unless set, frame time\n"
    "1/60 s, parameters named dither/dithering/jitter/taa_jitter off. A failing test names the "
    "first\n"
    "captured resource, in pipeline order, whose comparison fails.\n"
    "Exit codes: 0 all passed, 1 a test failed, 2 bad usage or a bad test script.\n";

int usage(const std::string& msg) {
    std::fprintf(stderr, "rgraph test: %s (see 'rgraph test --help')\n", msg.c_str());
    return kUsage;
}

}  // namespace

int goldenCommand(int argc, char** argv) {
    golden::RunnerOptions o;
    bool havePattern = false;
    for (int i = 2; i < argc; ++i) {
        std::string arg = argv[i];
        if (arg == "--help" || arg == "-h") {
            std::printf("%s", kHelp);
            return kOk;
        }
        if (arg == "--update") {
            o.update = true;
            continue;
        }
        if (arg == "--verbose") {
            o.verbose = true;
            continue;
        }
        if (arg.rfind("--", 0) == 0) {
            std::string name = arg.substr(2), value;
            if (auto eq = name.find('='); eq != std::string::npos) {
                value = name.substr(eq + 1);
                name = name.substr(0, eq);
            } else if (name == "report" || name == "junit" || name == "dir" || name == "images" ||
                       name == "out" || name == "device" || name == "shard") {
                if (i + 1 >= argc) return usage("option --" + name + " needs a value");
                value = argv[++i];
            }
            if (name == "report")
                o.reportDir = value;
            else if (name == "junit")
                o.junitFile = value;
            else if (name == "dir")
                o.testDir = value;
            else if (name == "images")
                o.imageDir = value;
            else if (name == "out")
                o.outDir = value;
            else if (name == "device") {
                if (value.empty() || value.size() > 3 ||
                    value.find_first_not_of("0123456789") != std::string::npos)
                    return usage("--device must be a device index (see 'rgraph devices')");
                o.device = static_cast<uint32_t>(std::stoul(value));
            } else if (name == "shard") {
                const auto slash = value.find('/');
                const std::string k = value.substr(0, slash),
                                  n = slash == std::string::npos ? "" : value.substr(slash + 1);
                auto whole = [](const std::string& s) {
                    return !s.empty() && s.size() <= 4 &&
                           s.find_first_not_of("0123456789") == std::string::npos;
                };
                if (!whole(k) || !whole(n) || std::stoul(k) < 1 || std::stoul(k) > std::stoul(n))
                    return usage("--shard must be K/N with 1 <= K <= N, got '" + value + "'");
                o.shard = static_cast<uint32_t>(std::stoul(k));
                o.shards = static_cast<uint32_t>(std::stoul(n));
            } else
                return usage("unknown option --" + name);
            if (value.empty()) return usage("option --" + name + " needs a value");
            continue;
        }
        if (havePattern)
            return usage("one PATTERN at most, got '" + o.pattern + "' and '" + arg + "'");
        o.pattern = arg;
        havePattern = true;
    }
    auto report = golden::runGoldenTests(o, stdout);
    if (!report) {
        std::fprintf(stderr, "rgraph test: error: %s\n", report.error().describe().c_str());
        const ErrorCode c = report.error().code;
        return c == ErrorCode::InvalidInput || c == ErrorCode::NotFound ||
                       c == ErrorCode::Unsupported
                   ? kUsage
                   : kFailed;
    }
    bool badInput = false, failed = false;
    for (const auto& t : report->tests) {
        badInput = badInput || (t.status == golden::TestStatus::Error && t.badInput);
        failed = failed || t.status != golden::TestStatus::Passed;
    }
    return badInput ? kUsage : failed ? kFailed : kOk;
}

}  // namespace rg

// The goldens on disk: the environment they record, which set a device compares with, comparing a
// capture with it, and blessing (rewriting it). Internal to the runner (runner.cpp).
//
// Goldens per device family. A test's goldens live in tests/golden/images/NAME/: that folder's
// golden.json says which device family made them (made_with.family; older files: the first word of
// made_with.driver, e.g. "llvmpipe") — the test's primary family. A device of another family
// compares with images/NAME/devices/FAMILY/ (its own golden.json) when that exists, by the
// comparisons the test states; and always also, by the test's `cross_device` bound (a perceptual
// metric on the display image), with the primary goldens — so no family's goldens drift from the
// reference's. Without goldens of its own, the cross-device bound alone decides; a test that states
// none compares with the primary goldens by its own comparisons (tests whose outputs every device
// makes alike: integer ids, exact patterns). `--update` writes the running device's family's set. A device's family is the first word of its Vulkan
// driver's name ("llvmpipe", "NVIDIA" → "nvidia", "radv"), or RG_DEVICE_FAMILY when set.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "golden/golden_test.h"
#include "golden/report.h"

namespace rg {
class Runtime;
}

namespace rg::golden {

inline constexpr const char* kProfileThreads =
    "2";  // the profile's LP_NUM_THREADS unless the environment sets one

// A path relative to the project root when inside it, else as given.
std::string relativeToRoot(const std::string& path);

RunEnvironment environmentOf(Runtime& rt);
std::string profileLine(const RunEnvironment& e);
nlohmann::ordered_json environmentJson(const RunEnvironment& e);
// "llvmpipe Mesa 22.3.6 (LLVM 15.0.6)" → "llvmpipe": the first word, lower case, [a-z0-9_-] only.
std::string deviceFamily(const std::string& driver);

// Which goldens a run on a device of `family` compares with (see above).
struct GoldenSet {
    std::string primaryDir;     // images/NAME
    std::string primaryFamily;  // "" when the test has no goldens yet
    std::string dir;            // the set this device reads and --update writes
    std::string family;         // the running device's
    bool foreign = false;       // family != primaryFamily (dir = primaryDir/devices/family)
    bool own = false;           // dir holds a golden.json
};
GoldenSet chooseGoldenSet(const std::string& primaryDir, const std::string& family);

bool samePixels(const Image& a, const Image& b);
void compareCapture(CaptureOutcome& co, const CaptureSpec& spec);
std::string verdicts(const CaptureOutcome& co);

// The cross-device checks of a foreign device's run: per capture the test's cross_device names, an
// outcome "RESOURCE@PRIMARY" comparing this run's image with the primary family's golden.
std::vector<CaptureOutcome> crossDeviceOutcomes(const GoldenTest& test,
                                                const std::vector<CaptureOutcome>& captures,
                                                const GoldenSet& set);

// Blesses the test's goldens in `dir`; returns what changed, one line each.
Result<std::vector<std::string>> bless(const GoldenTest& t, std::vector<CaptureOutcome>& caps,
                                       const std::string& dir, const RunEnvironment& env,
                                       const std::vector<std::string>& profileApplied);

}  // namespace rg::golden

// The goldens on disk: the environment they record, the set a device compares with, comparing
// and blessing (golden_set.h).
#include "golden/golden_set.h"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>

#include "runtime/runtime.h"
#include "golden/storage.h"

namespace fs = std::filesystem;

namespace rg::golden {

std::string relativeToRoot(const std::string& path) {
    std::error_code ec;
    const fs::path abs = fs::weakly_canonical(path, ec);
    const fs::path root = fs::weakly_canonical(projectRoot(), ec);
    const std::string rel = fs::relative(abs, root, ec).string();
    if (ec || rel.empty() || rel.rfind("..", 0) == 0) return path;
    return rel;
}

namespace {

std::string readCpuInfo(const char* key) {
    std::ifstream in("/proc/cpuinfo");
    std::string line;
    while (std::getline(in, line))
        if (line.rfind(key, 0) == 0) {
            auto colon = line.find(':');
            if (colon != std::string::npos) {
                std::string v = line.substr(colon + 1);
                v.erase(0, v.find_first_not_of(" \t"));
                return v;
            }
        }
    return "";
}

}  // namespace

RunEnvironment environmentOf(Runtime& rt) {
    RunEnvironment e;
    e.device = rt.gpu().deviceInfo().name;
    e.driver = rt.gpu().deviceInfo().driver;
    if (auto at = e.driver.find("Mesa "); at != std::string::npos) {
        e.mesa = e.driver.substr(at + 5);
        e.mesa = e.mesa.substr(0, e.mesa.find_first_of(" )"));
    }
    e.cpu = readCpuInfo("model name");
    // The features LLVM's code generation for lavapipe depends on: they decide the vector width
    // and whether FMA contracts, which is where 1-LSB differences between hosts come from.
    const std::string flags = " " + readCpuInfo("flags") + " ";
    for (const char* f : {"sse4_1", "sse4_2", "avx", "avx2", "fma", "f16c", "avx512f"})
        if (flags.find(" " + std::string(f) + " ") != std::string::npos)
            e.cpuFeatures += (e.cpuFeatures.empty() ? "" : " ") + std::string(f);
    if (const char* t = std::getenv("LP_NUM_THREADS")) e.lpNumThreads = t;
    if (const char* w = std::getenv("LP_NATIVE_VECTOR_WIDTH")) e.vectorWidth = w;
    const char* family = std::getenv("RG_DEVICE_FAMILY");
    e.family = deviceFamily(family && *family ? family : e.driver);
    return e;
}

std::string profileLine(const RunEnvironment& e) {
    std::string s = "LP_NUM_THREADS=" + e.lpNumThreads;
    if (!e.vectorWidth.empty()) s += ", LP_NATIVE_VECTOR_WIDTH=" + e.vectorWidth;
    s += ", frame time 1/60 s, dither and jitter parameters off";
    return s;
}

nlohmann::ordered_json environmentJson(const RunEnvironment& e) {
    nlohmann::ordered_json j;
    j["family"] = e.family;
    j["device"] = e.device;
    j["driver"] = e.driver;
    j["mesa"] = e.mesa;
    j["cpu"] = e.cpu;
    j["cpu_features"] = e.cpuFeatures;
    j["lp_num_threads"] = e.lpNumThreads;
    if (!e.vectorWidth.empty()) j["lp_native_vector_width"] = e.vectorWidth;
    return j;
}

bool samePixels(const Image& a, const Image& b) {
    if (a.width != b.width || a.height != b.height || a.channels != b.channels) return false;
    for (size_t i = 0; i < a.pixels.size(); ++i)
        if (!(a.pixels[i] == b.pixels[i] || (std::isnan(a.pixels[i]) && std::isnan(b.pixels[i]))))
            return false;
    return true;
}

std::string deviceFamily(const std::string& driver) {
    std::string f;
    for (char c : driver.substr(0, driver.find(' '))) {
        c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
        if (std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_') f += c;
    }
    return f.empty() ? "unknown" : f;
}

namespace {

// The family a golden.json records: made_with.family, else its driver's first word.
std::string recordedFamily(const std::string& sidecar) {
    std::ifstream in(sidecar);
    if (!in) return "";
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    auto j = nlohmann::ordered_json::parse(text, nullptr, false);
    if (j.is_discarded() || !j.contains("made_with") || !j["made_with"].is_object()) return "";
    const auto& m = j["made_with"];
    if (m.contains("family") && m["family"].is_string()) return m["family"];
    if (m.contains("driver") && m["driver"].is_string()) return deviceFamily(m["driver"]);
    return "";
}

}  // namespace

GoldenSet chooseGoldenSet(const std::string& primaryDir, const std::string& family) {
    GoldenSet s;
    s.primaryDir = s.dir = primaryDir;
    s.family = family;
    s.primaryFamily = recordedFamily((fs::path(primaryDir) / "golden.json").string());
    if (s.primaryFamily.empty() || s.primaryFamily == family) {
        s.own = !s.primaryFamily.empty();
        return s;
    }
    s.foreign = true;
    s.dir = (fs::path(primaryDir) / "devices" / family).string();
    std::error_code ec;
    s.own = fs::is_regular_file(fs::path(s.dir) / "golden.json", ec);
    return s;
}

std::vector<CaptureOutcome> crossDeviceOutcomes(const GoldenTest& test,
                                                const std::vector<CaptureOutcome>& captures,
                                                const GoldenSet& set) {
    std::vector<CaptureOutcome> out;
    if (!set.foreign) return out;
    for (const auto& spec : test.crossDevice) {
        auto it = std::find_if(captures.begin(), captures.end(), [&](const CaptureOutcome& c) {
            return c.resource == spec.resource;
        });
        if (it == captures.end()) continue;  // parseGoldenTest checked it is a capture
        CaptureOutcome co = *it;
        co.resource = spec.resource + "@" + set.primaryFamily;
        co.files.clear();
        co.note = "cross-device: this " + set.family + " run against the " + set.primaryFamily +
                  " goldens (the bound the test states for any device)";
        co.expectedFile =
            (fs::path(set.primaryDir) / (spec.resource + storageExtension(co.storage))).string();
        co.expected = Image{};
        std::error_code ec;
        if (fs::exists(co.expectedFile, ec))
            if (auto e = readStored(co.expectedFile, co.storage, isSrgbFormat(co.format)))
                co.expected = std::move(*e);
        if (co.expected.width > 0) {
            compareCapture(co, spec);
        } else {
            co.passed = false;
            co.comparisons.clear();
            for (const auto& cmp : spec.comparisons)
                co.comparisons.push_back(
                    ComparisonOutcome{cmp, {}, "no " + set.primaryFamily + " golden image", ""});
        }
        out.push_back(std::move(co));
    }
    return out;
}

void compareCapture(CaptureOutcome& co, const CaptureSpec& spec) {
    co.passed = true;
    co.comparisons.clear();
    for (const auto& cmp : spec.comparisons) {
        ComparisonOutcome o;
        o.spec = cmp;
        auto r = compare(co.actual, co.expected, cmp);
        if (r)
            o.result = std::move(*r);
        else
            o.error = r.error().message;
        co.passed = co.passed && o.passed();
        co.comparisons.push_back(std::move(o));
    }
}

std::string verdicts(const CaptureOutcome& co) {
    std::string s;
    for (const auto& c : co.comparisons)
        s += (s.empty() ? "" : ", ") + (c.error.empty() ? c.result.verdict() : c.error);
    return s;
}

namespace {

std::string sizeText(uint32_t w, uint32_t h) { return std::to_string(w) + "x" + std::to_string(h); }

nlohmann::ordered_json sidecarWithoutEnvironment(const GoldenTest& t,
                                                 const std::vector<CaptureOutcome>& caps,
                                                 const std::vector<std::string>& profileApplied) {
    nlohmann::ordered_json j;
    j["test"] = t.name;
    j["pipeline"] = t.pipeline;
    if (!t.scene.empty()) j["scene"] = t.scene;
    if (!t.camera.empty()) j["camera"] = t.camera;
    j["size"] = sizeText(t.width, t.height);
    j["frames"] = t.frames;
    nlohmann::ordered_json params = nlohmann::ordered_json::object();
    for (const auto& [k, v] : t.params)
        params[k] = v.isNumber()   ? nlohmann::ordered_json(v.asNumber())
                    : v.isBool()   ? nlohmann::ordered_json(v.asBool())
                    : v.isString() ? nlohmann::ordered_json(v.asString())
                                   : nlohmann::ordered_json(v.typeName());
    j["params"] = params;
    nlohmann::ordered_json captures = nlohmann::ordered_json::object();
    for (const auto& c : caps) {
        nlohmann::ordered_json cj;
        cj["file"] = c.resource + storageExtension(c.storage);
        cj["format"] = c.format;
        cj["storage"] = storageName(c.storage);
        cj["size"] = sizeText(c.actual.width, c.actual.height);
        nlohmann::ordered_json cmps = nlohmann::ordered_json::array();
        for (const auto& cmp : c.comparisons) cmps.push_back(cmp.spec.describe());
        cj["comparisons"] = cmps;
        captures[c.resource] = cj;
    }
    j["captures"] = captures;
    nlohmann::ordered_json profile;
    profile["lp_num_threads"] = kProfileThreads;
    profile["frame_time"] = "1/60 s";
    profile["applied"] = profileApplied;
    j["profile"] = profile;
    return j;
}

}  // namespace

// Blesses the test's goldens; returns what changed, one line each.
Result<std::vector<std::string>> bless(const GoldenTest& t, std::vector<CaptureOutcome>& caps,
                                       const std::string& dir, const RunEnvironment& env,
                                       const std::vector<std::string>& profileApplied) {
    std::vector<std::string> changes;
    bool wrote = false;
    std::set<std::string> keep = {"golden.json"};
    for (auto& c : caps) {
        const std::string file = c.resource + storageExtension(c.storage);
        keep.insert(file);
        const bool missing = c.expected.width == 0;
        const bool shapeChanged = !missing && (c.expected.width != c.actual.width ||
                                               c.expected.height != c.actual.height ||
                                               c.expected.channels != c.actual.channels);
        if (!missing && !shapeChanged && c.passed) {
            changes.push_back(samePixels(c.actual, c.expected)
                                  ? c.resource + ": unchanged"
                                  : c.resource + ": kept, within tolerance (" + verdicts(c) + ")");
            continue;
        }
        std::map<std::string, std::string> meta = {{"rgraph.test", t.name},
                                                   {"rgraph.resource", c.resource},
                                                   {"rgraph.format", c.format},
                                                   {"rgraph.device", env.device},
                                                   {"rgraph.driver", env.driver}};
        if (auto r = writeStored(c.expectedFile, c.actual, c.storage, isSrgbFormat(c.format), meta);
            !r)
            return std::unexpected(r.error());
        wrote = true;
        if (missing)
            changes.push_back(c.resource + ": new golden " + relativeToRoot(c.expectedFile) + " (" +
                              c.format + ", " + std::to_string(c.actual.width) + "x" +
                              std::to_string(c.actual.height) + ")");
        else if (shapeChanged)
            changes.push_back(c.resource + ": updated " + relativeToRoot(c.expectedFile) +
                              " (was " + std::to_string(c.expected.width) + "x" +
                              std::to_string(c.expected.height) + "x" +
                              std::to_string(c.expected.channels) + ")");
        else
            changes.push_back(c.resource + ": updated " + relativeToRoot(c.expectedFile) +
                              " (was: " + verdicts(c) + ")");
        c.expected = c.actual;
        c.note = changes.back();
        // The report shows the state after blessing.
        for (auto& cmp : c.comparisons) {
            auto r = compare(c.actual, c.expected, cmp.spec);
            if (r) cmp.result = std::move(*r), cmp.error.clear();
        }
        c.passed = true;
    }
    std::error_code ec;
    if (fs::is_directory(dir, ec))
        for (const auto& entry : fs::directory_iterator(dir, ec)) {
            const std::string name = entry.path().filename().string();
            const std::string ext = entry.path().extension().string();
            if ((ext == ".exr" || ext == ".png") && !keep.count(name)) {
                fs::remove(entry.path(), ec);
                changes.push_back("removed " + relativeToRoot(entry.path().string()) +
                                  " (no capture names it)");
                wrote = true;
            }
        }

    // golden.json: what the goldens were made with. The environment is only replaced when an
    // image was written, so re-running --update on another machine changes nothing.
    const std::string sidecar = (fs::path(dir) / "golden.json").string();
    nlohmann::ordered_json j = sidecarWithoutEnvironment(t, caps, profileApplied);
    std::string old;
    {
        std::ifstream in(sidecar);
        old.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    }
    nlohmann::ordered_json made = environmentJson(env);
    if (!wrote && !old.empty()) {
        auto parsed = nlohmann::ordered_json::parse(old, nullptr, false);
        if (!parsed.is_discarded() && parsed.contains("made_with")) made = parsed["made_with"];
    }
    j["made_with"] = made;
    const std::string text = j.dump(2) + "\n";
    if (text != old) {
        fs::create_directories(dir, ec);
        const std::string tmp = sidecar + ".tmp";
        std::ofstream(tmp) << text;
        fs::rename(tmp, sidecar, ec);
        if (ec) return fail(ErrorCode::Io, "cannot write '" + sidecar + "': " + ec.message());
        if (!wrote)
            changes.push_back("golden.json: updated (the test's captures or comparisons changed)");
    }
    return changes;
}

}  // namespace rg::golden

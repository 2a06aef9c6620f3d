#include "golden/runner.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <set>

#include <nlohmann/json.hpp>

#include "runtime/runtime.h"
#include "runtime/session.h"
#include "golden/golden_set.h"
#include "golden/golden_test.h"
#include "golden/storage.h"
#include "lua/declarations.h"

namespace fs = std::filesystem;

namespace rg::golden {

namespace {

using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point t) {
    return std::chrono::duration<double>(Clock::now() - t).count();
}

constexpr double kFrameTime = 1.0 / 60.0;  // the profile's fixed frame time
const std::vector<std::string> kProfileOff = {"dither", "dithering", "jitter", "taa_jitter"};
const char* kFrameTimeParam =
    "frame_time";  // a pipeline's own fixed frame time is pinned to kFrameTime

std::string fromRoot(const std::string& path) {
    if (fs::path(path).is_absolute()) return path;
    return (fs::path(projectRoot()) / path).string();
}

// ---- rendering a test ----
//
// Tests render through rg::Session (graph/runtime), so they see what `rgraph render` sees: scenes,
// cameras, reloads. Session takes the test's parameter values and frame callback through
// SessionOptions::params and SessionOptions::frameHook.

constexpr const char* kBufferFormat = "buffer:float32";

struct Capture {
    Image image;
    std::string format;
    std::string writer;
    int32_t order = -1;
};

struct Rendered {
    std::map<std::string, Capture> captures;
    std::vector<std::string> log;
    uint32_t validationMessages = 0;
};

struct TestError {
    Error error;
    bool badInput;
};

std::unexpected<TestError> testError(const Error& e) {
    const bool input = e.code == ErrorCode::InvalidInput || e.code == ErrorCode::NotFound ||
                       e.code == ErrorCode::Unsupported;
    return std::unexpected(TestError{e, input});
}

// What a test needs before it renders: the pipeline's file, the parameter values to set (the
// test's, then the determinism profile's) and the captures, all checked against the pipeline.
struct Prepared {
    std::string pipelineFile;
    std::map<std::string, Value> params;
    std::vector<std::string> profileLog;
    std::vector<std::string> captures;
};

std::expected<Prepared, TestError> prepare(Runtime& rt, const GoldenTest& test) {
    const std::string& where = test.file;
    Prepared p;
    p.pipelineFile = fromRoot(test.pipeline);
    std::error_code ec;
    if (!fs::is_regular_file(p.pipelineFile, ec))
        return testError(Error(ErrorCode::NotFound,
                               where + ": pipeline: no pipeline script '" + test.pipeline + "'"));
    LuaHost host(luaHostOptions(rt));
    auto pipeline = host.load(p.pipelineFile);
    if (!pipeline) return testError(pipeline.error());

    for (const auto& [name, value] : test.params) {
        const ParamDesc* d = pipeline->findParam(name);
        if (!d) {
            std::vector<std::string> names;
            for (const auto& q : pipeline->params) names.push_back(q.name);
            const std::string best = closestName(name, names);
            return testError(Error(ErrorCode::InvalidInput,
                                   where + ": params." + name +
                                       ": the pipeline has no parameter '" + name + "'" +
                                       (best.empty() ? "" : " (did you mean '" + best + "'?)")));
        }
        auto checked = checkParamValue(*d, value);
        if (!checked)
            return testError(Error(ErrorCode::InvalidInput,
                                   where + ": params." + name + ": " + checked.error().message));
        p.params[name] = *checked;
    }
    for (const auto& d : pipeline->params) {
        if (test.params.count(d.name)) continue;
        if (d.name == kFrameTimeParam && d.type == ParamType::Number &&
            checkParamValue(d, Value(kFrameTime))) {
            p.params[d.name] = Value(kFrameTime);
            p.profileLog.push_back("frame_time = 1/60 s");
            continue;
        }
        if (std::find(kProfileOff.begin(), kProfileOff.end(), d.name) == kProfileOff.end())
            continue;
        Value off = d.type == ParamType::Boolean  ? Value(false)
                    : d.type == ParamType::Choice ? Value("off")
                                                  : Value(0.0);
        if (d.type == ParamType::Choice &&
            std::find(d.choices.begin(), d.choices.end(), "off") == d.choices.end())
            off = Value("none");
        if (checkParamValue(d, off)) {
            p.params[d.name] = off;
            p.profileLog.push_back(d.name + " = " +
                                   (off.isBool()     ? "false"
                                    : off.isString() ? off.asString()
                                                     : "0"));
        }
    }

    for (const auto& c : test.captures) {
        if (!pipeline->graph.findResource(c.resource)) {
            std::vector<std::string> names;
            for (const auto& res : pipeline->graph.resources) names.push_back(res.name);
            const std::string best = closestName(c.resource, names);
            return testError(Error(ErrorCode::NotFound,
                                   where + ": captures." + c.resource +
                                       ": the pipeline has no resource named '" + c.resource + "'" +
                                       (best.empty() ? "" : " (did you mean '" + best + "'?)")));
        }
        p.captures.push_back(c.resource);
    }
    return p;
}

// Reads the captures back after the last frame, with the pass that last writes each.
std::expected<std::map<std::string, Capture>, TestError> readCaptures(
    gpu::Executor& executor, const std::vector<std::string>& names, const std::string& where) {
    std::map<std::string, Capture> out;
    if (auto r = executor.finish(); !r) return testError(r.error());
    const Plan& plan = executor.plan();
    for (const auto& name : names) {
        Capture c;
        const int32_t ri = plan.findResource(name);
        if (ri >= 0 && plan.resources[static_cast<size_t>(ri)].kind == ResourceKind::Buffer) {
            // A buffer is captured as an array of 32-bit floats: one row, one channel.
            auto bytes = executor.readbackBuffer(name);
            if (!bytes)
                return testError(Error(bytes.error().code, where + ": captures." + name + ": " +
                                                               bytes.error().message));
            c.image = Image(static_cast<uint32_t>(bytes->size() / 4), 1, 1);
            std::memcpy(c.image.pixels.data(), bytes->data(), c.image.pixels.size() * 4);
            c.format = kBufferFormat;
        } else {
            auto img = executor.readback(name);
            if (!img)
                return testError(Error(img.error().code,
                                       where + ": captures." + name + ": " + img.error().message));
            c.image = std::move(*img);
            if (ri >= 0)
                c.format = std::string(formatName(plan.resources[static_cast<size_t>(ri)].format));
        }
        // Every pass that writes it, in execution order: a difference in the captured (final)
        // contents can start at the first of them, so that one orders the captures.
        for (size_t i = 0; i < plan.passes.size(); ++i) {
            const bool writes = std::any_of(
                plan.passes[i].accesses.begin(), plan.passes[i].accesses.end(), [&](const auto& a) {
                    return static_cast<int32_t>(a.resource) == ri && usageWrites(a.usage);
                });
            if (!writes) continue;
            if (c.order < 0) c.order = static_cast<int32_t>(i);
            c.writer += (c.writer.empty() ? "'" : ", then '") + plan.passes[i].name + "'";
        }
        out[name] = std::move(c);
    }
    return out;
}

// Renders through a Session of its own runtime (a fresh device per test: no scene, persistent
// contents or memory carry over from one test to the next).
std::expected<Rendered, TestError> renderWithSession(const Prepared& p, const GoldenTest& test,
                                                     GoldenScript& script,
                                                     const RunnerOptions& options, std::FILE* out) {
    RuntimeOptions ro;
    ro.device = options.device;
    auto rt = Runtime::create(ro);
    if (!rt) return testError(rt.error());
    SessionOptions so;
    so.compile.outputWidth = test.width;
    so.compile.outputHeight = test.height;
    so.captures = p.captures;
    so.params = p.params;
    if (test.hasFrameCallback)
        so.frameHook = [&script](const FrameContext& ctx, const PipelineDesc& current) {
            return script.frame(ctx, current);
        };
    so.scene = test.scene.empty() ? std::string() : fromRoot(test.scene);
    so.camera = test.camera;
    so.bakeLightmap = bake::bakeLightmap;
    Session session(**rt, so);
    if (auto r = session.load(p.pipelineFile); !r) return testError(r.error());
    for (uint32_t f = 0; f < test.frames; ++f)
        if (auto r = session.frame(); !r) return testError(r.error());
    auto captures = readCaptures((*rt)->executor(), p.captures, test.file);
    if (!captures) return std::unexpected(captures.error());
    Rendered result;
    result.captures = std::move(*captures);
    for (const auto& line : session.log())
        if (line.rfind("frame ", 0) == 0) {
            result.log.push_back(line);
            if (options.verbose) std::fprintf(out, "        %s\n", line.c_str());
        }
    result.validationMessages = (*rt)->gpu().validationMessageCount();
    return result;
}

std::expected<Rendered, TestError> render(Runtime& rt, GoldenScript& script,
                                          const RunnerOptions& options, std::FILE* out) {
    const GoldenTest& test = script.test();
    auto prepared = prepare(rt, test);
    if (!prepared) return std::unexpected(prepared.error());
    std::expected<Rendered, TestError> r = renderWithSession(*prepared, test, script, options, out);
    if (r) {
        std::vector<std::string> log;
        for (const auto& line : prepared->profileLog) log.push_back("profile: " + line);
        r->log.insert(r->log.begin(), log.begin(), log.end());
    }
    return r;
}

// Writes actual, expected and diff heat maps of a failing capture under outDir/test/.
void writeArtefacts(CaptureOutcome& c, const std::string& dir) {
    const std::string base = (fs::path(dir) / c.resource).string();
    const std::string ext = storageExtension(c.storage);
    auto note = [&](const std::string& path, Result<void> r) {
        if (r)
            c.files.push_back(path);
        else
            c.note += (c.note.empty() ? "" : "; ") + r.error().message;
    };
    note(base + ".actual" + ext,
         writeStored(base + ".actual" + ext, c.actual, c.storage, isSrgbFormat(c.format), {}));
    if (c.storage != Storage::Png)
        note(base + ".actual.png",
             writePng(base + ".actual.png", previewImage(c.actual, c.display)));
    if (c.expected.width > 0) {
        note(base + ".expected" + ext, writeStored(base + ".expected" + ext, c.expected, c.storage,
                                                   isSrgbFormat(c.format), {}));
        if (c.storage != Storage::Png)
            note(base + ".expected.png",
                 writePng(base + ".expected.png", previewImage(c.expected, c.display)));
    }
    for (auto& cmp : c.comparisons) {
        if (!cmp.error.empty() || cmp.result.error.width == 0) continue;
        const std::string path = base + "." + metricName(cmp.spec.metric) + ".diff.png";
        auto r = writePng(path, heatMap(cmp.result.error, cmp.result.heatScale));
        if (r) cmp.diffFile = path;
        note(path, std::move(r));
    }
}

TestOutcome runOne(Runtime& rt, const std::string& file, const RunnerOptions& options,
                   const RunEnvironment& env, std::FILE* out) {
    const auto t0 = Clock::now();
    TestOutcome t;
    t.file = relativeToRoot(file);
    t.name = fs::path(file).stem().string();
    auto script = GoldenScript::load(file, t.file);
    if (!script) {
        t.status = TestStatus::Error;
        t.message = script.error().describe();
        t.badInput = true;
        t.seconds = secondsSince(t0);
        return t;
    }
    const GoldenTest& test = (*script)->test();
    t.doc = test.doc;
    t.pipeline = test.pipeline;
    t.golden = test.golden;
    t.width = test.width;
    t.height = test.height;
    t.frames = test.frames;

    auto rendered = render(rt, **script, options, out);
    if (!rendered) {
        t.status = TestStatus::Error;
        t.message = rendered.error().error.describe();
        t.badInput = rendered.error().badInput;
        t.seconds = secondsSince(t0);
        return t;
    }
    t.log = rendered->log;
    const uint32_t validationMessages = rendered->validationMessages;

    // Which goldens this device compares with (golden_set.h): its family's; for a family without
    // goldens of its own, the primary family's — through the cross-device bound alone where the
    // test states one, else by its own comparisons.
    const GoldenSet set =
        chooseGoldenSet((fs::path(options.imageDir) / test.golden).string(), env.family);
    const bool borrowed = set.foreign && !set.own && !options.update;
    const bool crossOnly = borrowed && !test.crossDevice.empty();
    for (const auto& spec : test.captures) {
        const Capture& cap = rendered->captures.at(spec.resource);
        CaptureOutcome co;
        co.resource = spec.resource;
        co.format = cap.format;
        co.storage = storageForFormat(cap.format);
        co.display = co.storage == Storage::Png && !isSrgbFormat(cap.format);
        co.writerPass = cap.writer;
        co.order = cap.order;
        co.actual = quantizeForStorage(cap.image, co.storage, isSrgbFormat(cap.format));
        co.expectedFile = (fs::path(borrowed ? set.primaryDir : set.dir) /
                           (spec.resource + storageExtension(co.storage)))
                              .string();
        std::error_code ec;
        if (fs::exists(co.expectedFile, ec)) {
            auto expected = readStored(co.expectedFile, co.storage, isSrgbFormat(cap.format));
            if (expected)
                co.expected = std::move(*expected);
            else
                co.note = "cannot read the golden: " + expected.error().message;
        } else {
            co.note = "no golden image " + relativeToRoot(co.expectedFile) +
                      ": bless it with 'rgraph test " + test.name + " --update'";
        }
        if (crossOnly) {
            co.passed = true;
            co.note = "not compared: no goldens of device family '" + set.family + "' (these are " +
                      set.primaryFamily + "'s); the cross-device bound decides";
        } else if (co.expected.width > 0) {
            compareCapture(co, spec);
        } else {
            co.passed = false;
            for (const auto& cmp : spec.comparisons)
                co.comparisons.push_back(ComparisonOutcome{cmp, {}, "no golden image", ""});
        }
        t.captures.push_back(std::move(co));
    }
    // Pipeline order: by the first pass that writes each capture, then by name — so a change in
    // the G-buffer pass names a G-buffer target first, not a later pass that also writes it.
    std::stable_sort(t.captures.begin(), t.captures.end(),
                     [](const CaptureOutcome& a, const CaptureOutcome& b) {
                         return a.order != b.order ? a.order < b.order : a.resource < b.resource;
                     });

    if (options.update && test.golden == test.name) {
        std::vector<std::string> applied;
        for (const auto& line : t.log)
            if (line.rfind("profile: ", 0) == 0) applied.push_back(line.substr(9));
        auto changes = bless(test, t.captures, set.dir, env, applied);
        if (!changes) {
            t.status = TestStatus::Error;
            t.message = changes.error().describe();
            t.seconds = secondsSince(t0);
            return t;
        }
        t.changes = std::move(*changes);
    } else if (options.update) {
        t.changes.push_back("not blessed: it compares with the goldens of '" + test.golden + "'");
    }

    // A foreign family's run also meets the test's cross-device bound against the primary goldens.
    // (Not when it borrowed them for its own comparisons: that is the same check, tighter.)
    if (!borrowed || crossOnly)
        for (auto& c : crossDeviceOutcomes(test, t.captures, set))
            t.captures.push_back(std::move(c));
    std::stable_sort(t.captures.begin(), t.captures.end(),
                     [](const CaptureOutcome& a, const CaptureOutcome& b) {
                         return a.order != b.order ? a.order < b.order : a.resource < b.resource;
                     });

    t.status = TestStatus::Passed;
    for (auto& c : t.captures) {
        if (c.passed) continue;
        t.status = TestStatus::Failed;
        if (t.firstDivergent.empty()) {
            t.firstDivergent = c.resource;
            t.message = "first divergent resource in pipeline order: '" + c.resource + "'" +
                        (c.writerPass.empty() ? "" : " (written by " + c.writerPass + ")") + ": " +
                        (c.expected.width == 0 ? c.note : verdicts(c));
        }
        writeArtefacts(c, (fs::path(options.outDir) / test.name).string());
    }
    if (t.status == TestStatus::Failed) {
        // Say when the goldens came from another device or driver: a likely cause of small differences.
        std::ifstream in(fs::path(set.own ? set.dir : set.primaryDir) / "golden.json");
        std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        auto j = nlohmann::ordered_json::parse(text, nullptr, false);
        if (!j.is_discarded() && j.contains("made_with")) {
            const auto& m = j["made_with"];
            const std::string dev = m.value("device", ""), drv = m.value("driver", ""),
                              feat = m.value("cpu_features", "");
            if (dev != env.device || drv != env.driver || feat != env.cpuFeatures)
                t.message += "\n(the goldens were made with " + dev + ", " + drv +
                             ", CPU features '" + feat + "'; this run: " + env.device + ", " +
                             env.driver + ", '" + env.cpuFeatures + "')";
        }
    }
    if (const uint32_t n = validationMessages; n > 0) {
        t.status = TestStatus::Failed;
        t.message = std::to_string(n) + " Vulkan validation message(s), printed above" +
                    (t.message.empty() ? "" : "; " + t.message);
    }
    t.seconds = secondsSince(t0);
    return t;
}

void print(std::FILE* out, const TestOutcome& t) {
    std::fprintf(out, "%-5s %-32s %6.2f s\n", testStatusName(t.status), t.name.c_str(), t.seconds);
    for (const auto& c : t.captures) {
        if (c.comparisons.empty() && !c.note.empty())
            std::fprintf(out, "        %-16s %s\n", c.resource.c_str(), c.note.c_str());
        else if (c.expected.width == 0)
            std::fprintf(out, "        %-16s %-44s %s\n", c.resource.c_str(), "no golden image",
                         c.resource == t.firstDivergent ? "FAIL  <- first divergent" : "FAIL");
        for (const auto& cmp : c.comparisons) {
            if (c.expected.width == 0) break;
            const std::string v = cmp.error.empty() ? cmp.result.verdict() : cmp.error;
            std::fprintf(out, "        %-16s %-44s %s\n", c.resource.c_str(), v.c_str(),
                         cmp.passed() ? "ok"
                                      : (c.resource == t.firstDivergent ? "FAIL  <- first divergent"
                                                                        : "FAIL"));
            if (!cmp.passed() && cmp.error.empty() && !cmp.result.detail.empty())
                std::fprintf(out, "        %-16s   %s\n", "", cmp.result.detail.c_str());
        }
        if (!c.files.empty()) {
            std::string files;
            for (const auto& f : c.files) files += (files.empty() ? "" : ", ") + relativeToRoot(f);
            std::fprintf(out, "        %-16s   wrote %s\n", "", files.c_str());
        }
    }
    for (const auto& line : t.changes) std::fprintf(out, "        update: %s\n", line.c_str());
    if (t.status != TestStatus::Passed && !t.message.empty()) {
        std::string m = t.message;
        for (size_t at = 0; (at = m.find('\n', at)) != std::string::npos; at += 9)
            m.replace(at, 1, "\n        ");
        std::fprintf(out, "        %s\n", m.c_str());
    }
    std::fflush(out);
}

}  // namespace

Result<RunReport> runGoldenTests(const RunnerOptions& optionsIn, std::FILE* out) {
    RunnerOptions options = optionsIn;
    if (options.testDir.empty()) options.testDir = projectRoot() + "/tests/golden";
    if (options.imageDir.empty()) options.imageDir = projectRoot() + "/tests/golden/images";
    auto files = findGoldenTests(options.testDir, options.pattern);
    if (!files) return std::unexpected(files.error());
    if (files->empty()) {
        auto all = findGoldenTests(options.testDir, "");
        std::string names;
        for (const auto& f : all ? *all : std::vector<std::string>{})
            names += (names.empty() ? "" : ", ") + fs::path(f).stem().string();
        return fail(ErrorCode::NotFound,
                    "no golden test matches '" + options.pattern + "' in " +
                        relativeToRoot(options.testDir) +
                        (names.empty() ? " (it has none)" : " (tests: " + names + ")"));
    }

    // This shard's tests: every shards-th by name, from the shard-th (N shards run each once).
    if (options.shards > 1) {
        std::sort(files->begin(), files->end(), [](const std::string& a, const std::string& b) {
            return fs::path(a).stem().string() < fs::path(b).stem().string();
        });
        std::vector<std::string> mine;
        for (size_t i = 0; i < files->size(); ++i)
            if (i % options.shards == options.shard - 1) mine.push_back((*files)[i]);
        std::fprintf(out, "rgraph test: shard %u/%u: %zu of %zu tests\n", options.shard,
                     options.shards, mine.size(), files->size());
        *files = std::move(mine);
    }
    // The determinism profile's thread count, before the Vulkan driver reads it.
    setenv("LP_NUM_THREADS", kProfileThreads, /*overwrite=*/0);
    const auto t0 = Clock::now();
    RuntimeOptions ro;
    ro.device = options.device;
    auto rt = Runtime::create(ro);
    if (!rt) return std::unexpected(rt.error());

    RunReport report;
    report.update = options.update;
    report.environment = environmentOf(**rt);
    report.profile = profileLine(report.environment);
    std::fprintf(out, "rgraph test: %zu golden test%s from %s on %s (%s; family %s; %s)\n",
                 files->size(), files->size() == 1 ? "" : "s",
                 relativeToRoot(options.testDir).c_str(), report.environment.device.c_str(),
                 report.environment.driver.c_str(), report.environment.family.c_str(),
                 report.profile.c_str());
    std::fflush(out);
    for (const auto& file : *files) {
        report.tests.push_back(runOne(**rt, file, options, report.environment, out));
        print(out, report.tests.back());
    }
    report.seconds = secondsSince(t0);
    std::fprintf(out, "rgraph test: %zu passed, %zu failed, %zu errors (%.2f s)\n",
                 report.count(TestStatus::Passed), report.count(TestStatus::Failed),
                 report.count(TestStatus::Error), report.seconds);
    if (!options.reportDir.empty()) {
        if (auto r = writeHtmlReport(options.reportDir, report); !r)
            return std::unexpected(r.error());
        std::fprintf(out, "rgraph test: report %s\n",
                     (fs::path(options.reportDir) / "index.html").string().c_str());
    }
    if (!options.junitFile.empty()) {
        if (auto r = writeJunit(options.junitFile, report); !r) return std::unexpected(r.error());
        std::fprintf(out, "rgraph test: JUnit %s\n", options.junitFile.c_str());
    }
    std::fflush(out);
    return report;
}

}  // namespace rg::golden

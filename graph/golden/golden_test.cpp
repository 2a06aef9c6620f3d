#include "golden/golden_test.h"

#include <fnmatch.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "lua/declarations.h"

namespace fs = std::filesystem;

namespace rg::golden {

namespace {

std::string quotedList(const std::vector<std::string>& names) {
    std::string s;
    for (const auto& n : names) s += (s.empty() ? "'" : ", '") + n + "'";
    return s;
}

std::string describeValue(const Value& v) {
    if (v.isNumber()) return formatNumber(v.asNumber());
    if (v.isString()) return "'" + v.asString() + "'";
    return v.typeName();
}

// Error builder: "<where>: <path>: <message>".
struct Errors {
    std::string where;
    std::unexpected<Error> operator()(const std::string& path, const std::string& msg,
                                      ErrorCode code = ErrorCode::InvalidInput) const {
        return fail(code, where + ": " + (path.empty() ? "" : path + ": ") + msg);
    }
};

std::string unknownField(const std::string& key, const std::vector<std::string>& known) {
    std::string best = closestName(key, known);
    return "unknown field" + (best.empty() ? std::string() : " (did you mean '" + best + "'?)") +
           "; expected one of: " + quotedList(known);
}

Result<double> number(const Value& v, const std::string& path, const Errors& err) {
    if (!v.isNumber() || std::isnan(v.asNumber()))
        return err(path, "expected a number, got " + describeValue(v));
    return v.asNumber();
}

Result<uint32_t> whole(const Value& v, const std::string& path, uint32_t lo, uint32_t hi,
                       const Errors& err) {
    if (!v.isNumber() || v.asNumber() != std::floor(v.asNumber()) || v.asNumber() < lo ||
        v.asNumber() > hi)
        return err(path, "expected a whole number in [" + std::to_string(lo) + ", " +
                             std::to_string(hi) + "], got " + describeValue(v));
    return static_cast<uint32_t>(v.asNumber());
}

Result<std::string> text(const Value& v, const std::string& path, const Errors& err) {
    if (!v.isString() || v.asString().empty())
        return err(path, "expected a non-empty string, got " + describeValue(v));
    return v.asString();
}

// The fields each metric takes besides metric, tolerance and channels.
std::vector<std::string> extraFields(Metric m) {
    switch (m) {
        case Metric::OverThreshold:
            return {"threshold"};
        case Metric::RelMean:
        case Metric::RelMax:
            return {"epsilon"};
        case Metric::Psnr:
            return {"peak"};
        case Metric::Angular:
            return {"encoding"};
        case Metric::Flip:
            return {"display", "ppd"};
        default:
            return {};
    }
}

Result<Comparison> parseComparison(const Value& v, const std::string& path, const Errors& err) {
    if (!v.isTable())
        return err(path, "expected a comparison table { metric = ..., tolerance = ... }, got " +
                             describeValue(v));
    const Value& metricV = v["metric"];
    if (metricV.isNil())
        return err(path + ".metric", "missing; expected one of: " + quotedList(metricNames()));
    if (!metricV.isString())
        return err(path + ".metric", "expected a metric name, got " + describeValue(metricV));
    auto metric = parseMetric(metricV.asString());
    if (!metric) {
        std::string best = closestName(metricV.asString(), metricNames());
        return err(path + ".metric", "unknown metric '" + metricV.asString() + "'" +
                                         (best.empty() ? "" : " (did you mean '" + best + "'?)") +
                                         "; expected one of: " + quotedList(metricNames()));
    }
    Comparison c;
    c.metric = *metric;
    const std::string name = metricName(c.metric);
    std::vector<std::string> allowed = {"metric", "tolerance", "channels"};
    for (const auto& f : extraFields(c.metric)) allowed.push_back(f);
    std::vector<std::string> every = {"metric", "tolerance", "channels", "threshold", "epsilon",
                                      "peak",   "encoding",  "display",  "ppd"};
    for (const auto& [key, value] : v.asTable()) {
        if (std::find(allowed.begin(), allowed.end(), key) != allowed.end()) continue;
        if (std::find(every.begin(), every.end(), key) != every.end())
            return err(path + "." + key, "metric '" + name + "' does not use '" + key +
                                             "'; its fields: " + quotedList(allowed));
        return err(path + "." + key, unknownField(key, allowed));
    }
    if (v.has("tolerance")) {
        auto t = number(v["tolerance"], path + ".tolerance", err);
        if (!t) return std::unexpected(t.error());
        if (c.metric != Metric::Psnr && *t < 0)
            return err(path + ".tolerance", "must not be negative, got " + formatNumber(*t));
        c.tolerance = *t;
    } else if (c.metric != Metric::Exact) {
        return err(path + ".tolerance", std::string("missing: metric '") + name + "' needs one (" +
                                            metricInfos()[static_cast<size_t>(c.metric)].meaning +
                                            ")");
    }
    if (v.has("channels")) {
        if (!v["channels"].isString())
            return err(path + ".channels", "expected letters of 'rgba' such as 'rgb', got " +
                                               describeValue(v["channels"]));
        auto ch = parseChannels(v["channels"].asString());
        if (!ch) return err(path + ".channels", ch.error().message);
        c.channels = *ch;
    }
    if (c.metric == Metric::OverThreshold) {
        if (!v.has("threshold"))
            return err(path + ".threshold",
                       "missing: over_threshold counts pixels whose difference exceeds it");
        auto t = number(v["threshold"], path + ".threshold", err);
        if (!t) return std::unexpected(t.error());
        if (*t < 0)
            return err(path + ".threshold", "must not be negative, got " + formatNumber(*t));
        c.threshold = *t;
    }
    if (v.has("epsilon")) {
        auto e = number(v["epsilon"], path + ".epsilon", err);
        if (!e) return std::unexpected(e.error());
        if (*e <= 0) return err(path + ".epsilon", "must be positive, got " + formatNumber(*e));
        c.epsilon = *e;
    }
    if (v.has("peak")) {
        auto p = number(v["peak"], path + ".peak", err);
        if (!p) return std::unexpected(p.error());
        if (*p <= 0) return err(path + ".peak", "must be positive, got " + formatNumber(*p));
        c.peak = *p;
    }
    if (v.has("ppd")) {
        auto p = number(v["ppd"], path + ".ppd", err);
        if (!p) return std::unexpected(p.error());
        if (*p <= 0 || *p > 1000)
            return err(path + ".ppd",
                       "expected pixels per degree in (0, 1000], got " + formatNumber(*p));
        c.pixelsPerDegree = *p;
    }
    if (v.has("encoding")) {
        const std::vector<std::string> names = {"signed", "unorm", "oct", "oct_unorm"};
        const Value& e = v["encoding"];
        auto it = e.isString() ? std::find(names.begin(), names.end(), e.asString()) : names.end();
        if (it == names.end())
            return err(path + ".encoding",
                       "expected one of: " + quotedList(names) + ", got " + describeValue(e));
        c.normals = static_cast<NormalEncoding>(it - names.begin());
    }
    if (v.has("display")) {
        const Value& d = v["display"];
        if (!d.isString() || (d.asString() != "linear" && d.asString() != "srgb"))
            return err(path + ".display", "expected 'linear' or 'srgb', got " + describeValue(d));
        c.display = d.asString() == "srgb" ? DisplayEncoding::Srgb : DisplayEncoding::Linear;
    }
    // Channel counts the metric needs (the image's own count is checked when comparing).
    if (c.metric == Metric::Angular && !c.channels.empty()) {
        const bool oct = c.normals == NormalEncoding::Oct || c.normals == NormalEncoding::OctUnorm;
        if (c.channels.size() != (oct ? 2u : 3u))
            return err(path + ".channels", std::string(oct ? "an octahedral normal needs 2 channels"
                                                           : "a normal needs 3 channels") +
                                               ", got '" + v["channels"].asString() + "'");
    }
    if (c.metric == Metric::Flip && !c.channels.empty() && c.channels.size() != 1 &&
        c.channels.size() != 3)
        return err(path + ".channels", "flip compares 1 (grey) or 3 (colour) channels, got '" +
                                           v["channels"].asString() + "'");
    return c;
}

}  // namespace

bool matchesPattern(const std::string& name, const std::string& pattern) {
    if (pattern.empty()) return true;
    return fnmatch(pattern.c_str(), name.c_str(), 0) == 0;
}

Result<std::vector<std::string>> findGoldenTests(const std::string& dir,
                                                 const std::string& pattern) {
    std::error_code ec;
    if (!fs::is_directory(dir, ec))
        return fail(ErrorCode::NotFound, "no golden test folder '" + dir + "'");
    std::vector<std::string> files;
    for (const auto& entry : fs::directory_iterator(dir, ec)) {
        if (!entry.is_regular_file() || entry.path().extension() != ".lua") continue;
        if (matchesPattern(entry.path().stem().string(), pattern))
            files.push_back(entry.path().string());
    }
    std::sort(files.begin(), files.end());
    return files;
}

Result<std::vector<uint32_t>> parseChannels(const std::string& letters) {
    std::vector<uint32_t> out;
    if (letters.empty())
        return fail(ErrorCode::InvalidInput, "expected letters of 'rgba' such as 'rgb', got ''");
    for (char ch : letters) {
        const std::string rgba = "rgba";
        auto pos = rgba.find(ch);
        if (pos == std::string::npos)
            return fail(ErrorCode::InvalidInput,
                        "expected letters of 'rgba' such as 'rgb', got '" + letters + "'");
        const uint32_t i = static_cast<uint32_t>(pos);
        if (std::find(out.begin(), out.end(), i) != out.end())
            return fail(ErrorCode::InvalidInput,
                        "channel '" + std::string(1, ch) + "' is named twice in '" + letters + "'");
        out.push_back(i);
    }
    return out;
}

Result<GoldenTest> parseGoldenTest(const Value& table, bool hasFrame, const std::string& name,
                                   const std::string& where) {
    const Errors err{where};
    if (!table.isTable())
        return err("",
                   "a golden test script returns a table { pipeline = ..., size = ..., captures = "
                   "... }, got " +
                       describeValue(table));
    static const std::vector<std::string> known = {"doc",    "pipeline", "scene",       "camera",
                                                   "size",   "frames",   "params",      "frame",
                                                   "golden", "captures", "cross_device"};
    for (const auto& [key, value] : table.asTable())
        if (std::find(known.begin(), known.end(), key) == known.end())
            return err(key, unknownField(key, known));

    GoldenTest t;
    t.name = name;
    t.file = where;
    t.golden = name;
    t.hasFrameCallback = hasFrame;
    if (table.has("doc")) {
        if (!table["doc"].isString())
            return err("doc", "expected a string, got " + describeValue(table["doc"]));
        t.doc = table["doc"].asString();
    }
    if (!table.has("pipeline"))
        return err("pipeline",
                   "missing: the pipeline script to render (e.g. 'scripts/pipelines/test.lua')");
    auto pipeline = text(table["pipeline"], "pipeline", err);
    if (!pipeline) return std::unexpected(pipeline.error());
    t.pipeline = *pipeline;
    if (table.has("scene")) {
        auto scene = text(table["scene"], "scene", err);
        if (!scene) return std::unexpected(scene.error());
        t.scene = *scene;
    }
    if (table.has("camera")) {
        auto camera = text(table["camera"], "camera", err);
        if (!camera) return std::unexpected(camera.error());
        if (t.scene.empty()) return err("camera", "names a camera of the scene: set 'scene' too");
        t.camera = *camera;
    }
    if (!table.has("size"))
        return err("size", "missing: the output size { width, height }, at most 256 x 256");
    {
        const Value& s = table["size"];
        if (!s.isList() || s.asList().size() != 2 || !s.asList()[0].isNumber() ||
            !s.asList()[1].isNumber())
            return err("size", "expected { width, height }, got " + describeValue(s));
        auto w = whole(s.asList()[0], "size[1]", 1, kMaxGoldenSize, err);
        if (!w) return std::unexpected(w.error());
        auto h = whole(s.asList()[1], "size[2]", 1, kMaxGoldenSize, err);
        if (!h) return std::unexpected(h.error());
        t.width = *w;
        t.height = *h;
    }
    if (table.has("frames")) {
        auto f = whole(table["frames"], "frames", 1, kMaxFrames, err);
        if (!f) return std::unexpected(f.error());
        t.frames = *f;
    }
    if (table.has("params")) {
        const Value& p = table["params"];
        if (!p.isTable())
            return err("params", "expected a table of parameter values { name = value }, got " +
                                     describeValue(p));
        t.params = p.asTable();
    }
    if (table.has("golden")) {
        auto g = text(table["golden"], "golden", err);
        if (!g) return std::unexpected(g.error());
        if (g->find_first_of("/\\") != std::string::npos || *g == "." || *g == "..")
            return err("golden", "expected the name of another golden test, got '" + *g + "'");
        t.golden = *g;
    }
    if (!table.has("captures"))
        return err(
            "captures",
            "missing: the resources to compare { resource = { metric = ..., tolerance = ... } }");
    const Value& caps = table["captures"];
    if (!caps.isTable() || caps.asTable().empty())
        return err("captures",
                   "expected a table { resource = { metric = ..., tolerance = ... } } with at "
                   "least one entry, got " +
                       describeValue(caps));
    auto specs = [&](const Value& table,
                     const std::string& field) -> Result<std::vector<CaptureSpec>> {
        std::vector<CaptureSpec> out;
        for (const auto& [resource, spec] : table.asTable()) {
            const std::string path = field + "." + resource;
            CaptureSpec cap;
            cap.resource = resource;
            if (spec.isList()) {
                if (spec.asList().empty()) return err(path, "expected at least one comparison");
                for (size_t i = 0; i < spec.asList().size(); ++i) {
                    auto c = parseComparison(spec.asList()[i],
                                             path + "[" + std::to_string(i + 1) + "]", err);
                    if (!c) return std::unexpected(c.error());
                    cap.comparisons.push_back(*c);
                }
            } else {
                auto c = parseComparison(spec, path, err);
                if (!c) return std::unexpected(c.error());
                cap.comparisons.push_back(*c);
            }
            out.push_back(std::move(cap));
        }
        return out;
    };
    auto captures = specs(caps, "captures");
    if (!captures) return std::unexpected(captures.error());
    t.captures = std::move(*captures);
    if (table.has("cross_device")) {
        const Value& cross = table["cross_device"];
        if (!cross.isTable() || cross.asTable().empty())
            return err("cross_device",
                       "expected a table { capture = { metric = ..., tolerance = ... } } naming "
                       "captures, got " +
                           describeValue(cross));
        for (const auto& [resource, spec] : cross.asTable())
            if (!caps.has(resource))
                return err("cross_device." + resource,
                           "not one of the test's captures (a cross-device bound compares a "
                           "captured image with the primary device family's golden)");
        auto bounds = specs(cross, "cross_device");
        if (!bounds) return std::unexpected(bounds.error());
        t.crossDevice = std::move(*bounds);
    }
    return t;
}

}  // namespace rg::golden

#include "accuracy.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "golden/metrics.h"
#include "runtime/session.h"

namespace fs = std::filesystem;

namespace rg {

namespace {

struct Frame {
    Image hdr;  // cd/m²
    Image depth;
};

Result<Frame> renderCase(Runtime& rt, const AccuracyOptions& o, const AccuracyCase& c,
                         const std::string& model, bool reference, uint32_t seed) {
    SessionOptions so;
    so.bakeLightmap = bake::bakeLightmap;
    so.compile.outputWidth = o.width;
    so.compile.outputHeight = o.height;
    so.scene = projectRoot() + "/scripts/scenes/accuracy.lua";
    so.sceneArgs = {{"light", c.light}, {"placement", c.placement}, {"material", c.material}};
    so.captures = {"hdr", "depth"};
    so.params["exposure_mode"] = Value("manual");
    // The real-time image against the reference pixel by pixel: not jittered.
    so.paramsIfDeclared["taa_jitter"] = Value(false);
    so.paramsIfDeclared["specular_aa"] = Value(false);  // roughness as the scene gives it
    if (reference) {
        so.params["reference_seed"] = Value(static_cast<double>(seed));
        so.params["reference_samples"] = Value(static_cast<double>(o.samples));
    } else
        so.params["area_lights"] = Value(model);
    Session s(rt, so);
    if (auto r = s.load(projectRoot() + (reference ? "/scripts/pipelines/reference.lua"
                                                   : "/scripts/pipelines/deferred.lua"));
        !r)
        return std::unexpected(r.error());
    const uint32_t frames = reference ? o.frames : 1;
    for (uint32_t f = 0; f < frames; ++f)
        if (auto r = s.frame(); !r) return std::unexpected(r.error());
    Frame out;
    auto hdr = readAbsoluteHdr(rt.executor(), s.pipeline());
    auto depth = rt.executor().readback("depth");
    if (!hdr) return std::unexpected(hdr.error());
    if (!depth) return std::unexpected(depth.error());
    out.hdr = std::move(hdr->image);
    out.depth = std::move(*depth);
    return out;
}

}  // namespace

Result<std::vector<AccuracyCase>> runAccuracy(Runtime& rt, const AccuracyOptions& o) {
    std::vector<AccuracyCase> cases;
    const size_t count = o.lights.size() * o.placements.size() * o.materials.size();
    size_t index = 0;
    for (const auto& l : o.lights)
        for (const auto& p : o.placements)
            for (const auto& m : o.materials) {
                AccuracyCase scene{l, p, m};
                if (o.progress) o.progress(scene.name(), index++, count);
                // The reference once, in two independent halves; each model against it.
                auto a = renderCase(rt, o, scene, "", true, 1);
                if (!a) return std::unexpected(a.error());
                auto b = renderCase(rt, o, scene, "", true, 2);
                if (!b) return std::unexpected(b.error());
                const size_t n = size_t(o.width) * o.height;
                Image reference = a->hdr;
                for (size_t i = 0; i < reference.pixels.size(); ++i)
                    reference.pixels[i] = 0.5f * (a->hdr.pixels[i] + b->hdr.pixels[i]);
                double peak = 0.0;
                for (size_t i = 0; i < n; ++i)
                    if (a->depth.pixels[i] < 1.0f)
                        for (int ch = 0; ch < 3; ++ch)
                            peak = std::max(peak, double(reference.pixels[i * 4 + size_t(ch)]));
                for (const auto& model : o.models) {
                    AccuracyCase c = scene;
                    c.model = model;
                    auto realtime = renderCase(rt, o, c, model, false, 0);
                    if (!realtime) return std::unexpected(realtime.error());
                    c.realtime = realtime->hdr;
                    c.reference = reference;
                    c.error = Image(o.width, o.height, 1);
                    std::vector<double> errors;
                    double rtSum = 0.0, refSum = 0.0, noise = 0.0;
                    for (size_t i = 0; i < n; ++i) {
                        if (a->depth.pixels[i] >= 1.0f) continue;
                        double pixelError = 0.0;
                        int lit = 0;
                        for (int ch = 0; ch < 3; ++ch) {
                            const size_t k = i * 4 + size_t(ch);
                            const double ref = c.reference.pixels[k], rtv = c.realtime.pixels[k];
                            if (!(ref >= 0.01 * peak) || !std::isfinite(rtv)) continue;
                            const double e = std::abs(rtv - ref) / ref;
                            errors.push_back(e);
                            pixelError += e, ++lit;
                            rtSum += rtv, refSum += ref;
                            noise += std::abs(double(a->hdr.pixels[k]) - double(b->hdr.pixels[k])) /
                                     (2.0 * ref);
                        }
                        if (lit) c.error.pixels[i] = static_cast<float>(pixelError / lit);
                    }
                    c.pixels = errors.size();
                    if (!errors.empty()) {
                        double sum = 0.0;
                        for (double e : errors) sum += e;
                        c.meanError = sum / double(errors.size());
                        c.referenceNoise = noise / double(errors.size());
                        std::sort(errors.begin(), errors.end());
                        c.p95Error = errors[std::min(errors.size() - 1,
                                                     size_t(0.95 * double(errors.size())))];
                        c.energyError = refSum > 0.0 ? rtSum / refSum - 1.0 : 0.0;
                    }
                    cases.push_back(std::move(c));
                }
            }
    return cases;
}

std::string accuracyTable(const std::vector<AccuracyCase>& cases) {
    std::string out;
    char line[256];
    std::snprintf(line, sizeof line, "%-36s %10s %10s %10s %12s\n", "case", "mean", "p95", "energy",
                  "ref. noise");
    out += line;
    for (const auto& c : cases) {
        std::snprintf(line, sizeof line, "%-36s %9.2f%% %9.2f%% %+9.2f%% %11.2f%%\n",
                      c.name().c_str(), c.meanError * 100.0, c.p95Error * 100.0,
                      c.energyError * 100.0, c.referenceNoise * 100.0);
        out += line;
    }
    return out;
}

Result<void> writeAccuracyReport(const std::vector<AccuracyCase>& cases, const std::string& dir) {
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec) return fail(ErrorCode::Io, "cannot create '" + dir + "': " + ec.message());
    std::ofstream html(dir + "/index.html");
    if (!html) return fail(ErrorCode::Io, "cannot write '" + dir + "/index.html'");
    html << "<!doctype html>\n<html><head><meta charset=\"utf-8\"><title>rgraph accuracy</title>\n"
         << "<style>body{font-family:sans-serif;background:#111;color:#ddd}table{border-collapse:"
            "collapse}"
         << "td,th{padding:4px 10px;border-bottom:1px solid "
            "#333;text-align:right}td:first-child{text-align:left}"
         << "img{image-rendering:pixelated;width:240px}</style></head><body>\n"
         << "<h1>Area lights: real-time against the reference mode</h1>\n"
         << "<p>Relative error over the pixels the reference lights above 1 % of its peak; heat "
            "map 0 (black) to 20 % (yellow) and beyond.</p>\n"
         << "<table><tr><th>case</th><th>mean</th><th>p95</th><th>energy</th><th>reference "
            "noise</th><th>heat map</th></tr>\n";
    for (const auto& c : cases) {
        std::string file = c.light + "_" + c.placement + "_" + c.material + "_" + c.model + ".png";
        Image map = golden::heatMap(c.error, 0.2f);
        if (auto r = writePng(dir + "/" + file, map); !r) return r;
        char row[512];
        std::snprintf(row, sizeof row,
                      "<tr><td>%s</td><td>%.2f %%</td><td>%.2f %%</td><td>%+.2f %%</td><td>%.2f "
                      "%%</td><td><img src=\"%s\"></td></tr>\n",
                      c.name().c_str(), c.meanError * 100.0, c.p95Error * 100.0,
                      c.energyError * 100.0, c.referenceNoise * 100.0, file.c_str());
        html << row;
    }
    html << "</table></body></html>\n";
    if (!html) return fail(ErrorCode::Io, "cannot write '" + dir + "/index.html'");
    return {};
}

}  // namespace rg

#include "accuracy_ibl.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <thread>

#include <unistd.h>

#include <glm/geometric.hpp>

#include "golden/metrics.h"
#include "lighting/brdf.h"
#include "runtime/session.h"
#include "scene/environment.h"

namespace fs = std::filesystem;

namespace rg {

namespace {

constexpr double kPi = 3.14159265358979;

// rgCubeDirection (lib/environment.glsl): the direction of cube face `face` at uv in [0, 1]².
glm::dvec3 cubeDirection(uint32_t face, double u, double v) {
    const double s = u * 2 - 1, t = v * 2 - 1;
    const glm::dvec3 d = face == 0   ? glm::dvec3(1, -t, -s)
                         : face == 1 ? glm::dvec3(-1, -t, s)
                         : face == 2 ? glm::dvec3(s, 1, t)
                         : face == 3 ? glm::dvec3(s, -1, -t)
                         : face == 4 ? glm::dvec3(s, -t, 1)
                                     : glm::dvec3(-s, -t, -1);
    return glm::normalize(d);
}

// Every texel of a cube (green): its direction and exact solid angle (the area of its square on
// the unit cube's face, projected: atan2(xy, sqrt(x² + y² + 1)) at its corners).
struct CubeTexels {
    std::vector<glm::dvec3> direction;
    std::vector<double> radiance, solidAngle;
};
CubeTexels cubeTexels(const std::vector<Image>& faces) {
    CubeTexels c;
    const uint32_t n = faces[0].width;
    auto area = [](double x, double y) { return std::atan2(x * y, std::sqrt(x * x + y * y + 1)); };
    for (uint32_t f = 0; f < 6; ++f)
        for (uint32_t y = 0; y < n; ++y)
            for (uint32_t x = 0; x < n; ++x) {
                const double a0 = 2.0 * x / n - 1, b0 = 2.0 * y / n - 1, a1 = a0 + 2.0 / n,
                             b1 = b0 + 2.0 / n;
                c.solidAngle.push_back(area(a0, b0) - area(a0, b1) - area(a1, b0) + area(a1, b1));
                c.direction.push_back(cubeDirection(f, (x + 0.5) / n, (y + 0.5) / n));
                c.radiance.push_back(faces[f].at(x, y, 1));
            }
    return c;
}

// The split sum's pre-filter with v = n: Σ L D(h) (n·l) Ω / Σ D(h) (n·l) Ω.
double exactPrefilter(const CubeTexels& c, glm::dvec3 n, double alpha) {
    const double a2 = alpha * alpha;
    double sum = 0.0, weight = 0.0;
    for (size_t i = 0; i < c.direction.size(); ++i) {
        const glm::dvec3& l = c.direction[i];
        const double nl = glm::dot(n, l);
        if (nl <= 0) continue;
        const double nh = glm::dot(n, glm::normalize(n + l));
        const double d = nh * nh * (a2 - 1) + 1;
        const double w = a2 / (kPi * d * d) * nl * c.solidAngle[i];
        sum += w * c.radiance[i];
        weight += w;
    }
    return sum / weight;
}

double exactIrradiance(const CubeTexels& c, glm::dvec3 n) {
    double e = 0.0;
    for (size_t i = 0; i < c.direction.size(); ++i)
        e += c.radiance[i] * std::max(0.0, glm::dot(n, c.direction[i])) * c.solidAngle[i];
    return e;
}

// Order-2 SH irradiance of env_sh's green coefficients (Ramamoorthi & Hanrahan 2001; the basis
// order and constants of lib/environment.glsl's rgShIrradiance).
double shIrradiance(const float* sh, glm::dvec3 n) {
    const double y[9] = {0.282095,
                         0.488603 * n.y,
                         0.488603 * n.z,
                         0.488603 * n.x,
                         1.092548 * n.x * n.y,
                         1.092548 * n.y * n.z,
                         0.315392 * (3 * n.z * n.z - 1),
                         1.092548 * n.x * n.z,
                         0.546274 * (n.x * n.x - n.y * n.y)};
    const double a[9] = {kPi,     2 * kPi / 3, 2 * kPi / 3, 2 * kPi / 3, kPi / 4,
                         kPi / 4, kPi / 4,     kPi / 4,     kPi / 4};
    double e = 0.0;
    for (int i = 0; i < 9; ++i) e += a[i] * y[i] * sh[4 * i + 1];
    return std::max(e, 0.0);
}

// f(i) for i in [0, n) on every core.
template <typename F>
void parallel(size_t n, F f) {
    std::atomic<size_t> next{0};
    std::vector<std::thread> threads;
    const size_t cores = std::max(1u, std::thread::hardware_concurrency());
    for (size_t t = 0; t < std::min(cores, n); ++t)
        threads.emplace_back([&] {
            for (size_t i; (i = next++) < n;) f(i);
        });
    for (std::thread& t : threads) t.join();
}

// The directions measured: n × n of each face at their cells' centres, face after face.
std::vector<glm::dvec3> directions(uint32_t n) {
    std::vector<glm::dvec3> d;
    for (uint32_t f = 0; f < 6; ++f)
        for (uint32_t k = 0; k < n * n; ++k)
            d.push_back(cubeDirection(f, (k % n + 0.5) / n, (k / n + 0.5) / n));
    return d;
}
// The error map of values laid out as `directions` lays them: faces side by side.
Image faceMap(const std::vector<double>& values, uint32_t n) {
    Image img(6 * n, n, 1);
    for (size_t i = 0; i < values.size(); ++i) {
        const uint32_t f = uint32_t(i / (n * n)), k = uint32_t(i % (n * n));
        img.at(f * n + k % n, k / n, 0) = float(values[i]);
    }
    return img;
}

Result<IblEnvironmentAccuracy> measure(Runtime& rt, const IblAccuracyOptions& o,
                                       const std::string& name, const std::string& environment,
                                       double& dfgWorst, size_t& dfgTexels) {
    SessionOptions so;
    so.compile.outputWidth = 32;
    so.compile.outputHeight = 32;
    so.scene = projectRoot() + "/scripts/scenes/furnace.lua";  // its environment replaced
    so.environment = environment;
    so.environmentSun = o.sun;
    so.captures = {"env_source", "env_specular", "env_sh", "dfg"};
    Session s(rt, so);
    if (auto r = s.load(projectRoot() + "/scripts/pipelines/deferred.lua"); !r)
        return std::unexpected(r.error());
    if (auto r = s.frame(); !r) return std::unexpected(r.error());
    if (auto r = rt.executor().finish(); !r) return std::unexpected(r.error());
    std::vector<Image> source;
    for (uint32_t f = 0; f < 6; ++f) {
        auto img = rt.executor().readback("env_source", f, 0);
        if (!img) return std::unexpected(img.error());
        source.push_back(std::move(*img));
    }
    const CubeTexels texels = cubeTexels(source);
    IblEnvironmentAccuracy out;
    out.name = name;
    const uint32_t n = std::max(1u, o.directionsPerFace);
    const std::vector<glm::dvec3> dirs = directions(n);

    auto bytes = rt.executor().readbackBuffer("env_sh");
    if (!bytes) return std::unexpected(bytes.error());
    if (bytes->size() < 9 * 16) return fail(ErrorCode::Device, "env_sh read back under 9 vec4");
    float sh[36];
    std::memcpy(sh, bytes->data(), sizeof sh);
    std::vector<double> exact(dirs.size()), error(dirs.size());
    parallel(dirs.size(), [&](size_t i) { exact[i] = exactIrradiance(texels, dirs[i]); });
    for (double e : exact) out.peakIrradiance = std::max(out.peakIrradiance, e);
    for (size_t i = 0; i < dirs.size(); ++i) {
        error[i] = std::abs(shIrradiance(sh, dirs[i]) / exact[i] - 1.0);
        if (exact[i] >= 0.25 * out.peakIrradiance)
            out.shLitWorst = std::max(out.shLitWorst, error[i]), ++out.shLit;
        else
            out.shDimWorst = std::max(out.shDimWorst, error[i]), out.shDimMean += error[i],
            ++out.shDim;
    }
    if (out.shDim) out.shDimMean /= double(out.shDim);
    out.shError = faceMap(error, n);

    // Each mip at its own texels' directions: n × n per face (fewer where the mip is smaller).
    auto first = rt.executor().readback("env_specular", 0, 0);
    if (!first) return std::unexpected(first.error());
    uint32_t mips = 0;
    for (uint32_t size = first->width; size >= 1; size /= 2) ++mips;
    for (uint32_t m = 1; m < mips; ++m) {
        IblMipAccuracy mip;
        mip.mip = m;
        mip.linearRoughness = std::pow(double(m) / (mips - 1), 2.0);
        const double alpha = std::max(mip.linearRoughness * mip.linearRoughness, 1e-3);
        // The lobe (half its weight within ~2α of n) against two source texels (2 / size rad at a
        // face's centre): narrower, the reference takes texel centres as they are while the
        // filter interpolates between them, and at a sharp edge the two part.
        mip.resolved = 2.0 * alpha >= 2.0 * (2.0 / source[0].width);
        std::vector<Image> faces;
        for (uint32_t f = 0; f < 6; ++f) {
            auto img = rt.executor().readback("env_specular", f, m);
            if (!img) return std::unexpected(img.error());
            faces.push_back(std::move(*img));
        }
        const uint32_t size = faces[0].width, k = std::min(n, size);
        std::vector<double> errors(size_t(6) * k * k);
        parallel(errors.size(), [&](size_t i) {
            const uint32_t f = uint32_t(i / (k * k)), c = uint32_t(i % (k * k));
            // The texel at the centre of cell c of a k × k grid over the face.
            const uint32_t x = (c % k) * size / k + size / (2 * k),
                           y = (c / k) * size / k + size / (2 * k);
            const glm::dvec3 dir = cubeDirection(f, (x + 0.5) / size, (y + 0.5) / size);
            errors[i] = std::abs(faces[f].at(x, y, 1) / exactPrefilter(texels, dir, alpha) - 1.0);
        });
        for (double e : errors) mip.worst = std::max(mip.worst, e), mip.mean += e;
        mip.mean /= double(errors.size());
        mip.error = faceMap(errors, k);
        out.mips.push_back(std::move(mip));
    }

    // The DFG table's texel centres against the integrators (roughness ≥ 0.1: below it
    // standardAlpha's 1e-3 floor differs from the table's α = r²), once.
    if (dfgTexels == 0) {
        auto dfg = rt.executor().readback("dfg");
        if (!dfg) return std::unexpected(dfg.error());
        const uint32_t w = dfg->width, h = dfg->height;
        for (uint32_t j = h / 8 - 1; j < h; j += h / 8)
            for (uint32_t i = 3; i < w; i += w / 8) {
                const float NdotV = (float(i) + 0.5f) / float(w), r = (float(j) + 0.5f) / float(h);
                dfgWorst =
                    std::max({dfgWorst,
                              std::abs(dfg->at(i, j, 0) - brdf::specularAlbedo(NdotV, r, 1, 0, 96)),
                              std::abs(dfg->at(i, j, 1) - brdf::specularAlbedo(NdotV, r, 0, 1, 96)),
                              std::abs(dfg->at(i, j, 2) - brdf::diffuseAlbedo(NdotV, r, 96))});
                ++dfgTexels;
            }
    }
    return out;
}

}  // namespace

bool IblEnvironmentAccuracy::pass() const {
    return shLitWorst <= kIblShLitBound &&
           std::all_of(mips.begin(), mips.end(), [](const auto& m) { return m.pass(); });
}

bool IblAccuracy::pass() const {
    return dfgWorst <= kIblDfgBound && std::all_of(environments.begin(), environments.end(),
                                                   [](const auto& e) { return e.pass(); });
}

Result<void> writeSyntheticSunSky(const std::string& path) {
    const uint32_t w = 1024, h = 512;
    Image sky(w, h, 3);
    const glm::dvec3 sun = glm::normalize(glm::dvec3(0.3, std::tan(40.0 * kPi / 180.0), -1.0));
    const double cosRadius = std::cos(0.25 * kPi / 180.0);
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) {
            int inside = 0;
            for (int sy = 0; sy < 4; ++sy)
                for (int sx = 0; sx < 4; ++sx) {
                    const glm::dvec3 d(equirectDirection(
                        {float((x + (sx + 0.5) / 4) / w), float((y + (sy + 0.5) / 4) / h)}));
                    inside += glm::dot(d, sun) >= cosRadius;
                }
            for (uint32_t c = 0; c < 3; ++c)
                sky.at(x, y, c) = 10.0f + 4e4f * static_cast<float>(inside) / 16.0f;
        }
    return writeExr(path, {{"", {"R", "G", "B"}, sky}});
}

Result<IblAccuracy> runIblAccuracy(Runtime& rt, const IblAccuracyOptions& o) {
    IblAccuracy out;
    for (size_t i = 0; i < o.environments.size(); ++i) {
        const std::string& e = o.environments[i];
        if (o.progress) o.progress(e, i, o.environments.size());
        std::string file = e;
        if (e == "synthetic") {
            const std::string dir =
                o.scratchDir.empty() ? fs::temp_directory_path().string() : o.scratchDir;
            file = dir + "/rgraph_synthetic_sun_" + std::to_string(::getpid()) + ".exr";
            if (auto r = writeSyntheticSunSky(file); !r) return std::unexpected(r.error());
        }
        auto env = measure(rt, o, e == "synthetic" || e == "sky" ? e : fs::path(e).stem().string(),
                           file, out.dfgWorst, out.dfgTexels);
        if (e == "synthetic") {
            std::error_code ec;
            fs::remove(file, ec);
        }
        if (!env) return std::unexpected(env.error());
        out.environments.push_back(std::move(*env));
    }
    return out;
}

std::string iblAccuracyTable(const IblAccuracy& r) {
    std::string out;
    char line[256];
    for (const auto& e : r.environments) {
        std::snprintf(line, sizeof line,
                      "%s: SH irradiance (peak %.4g lux): %zu lit directions worst %.2f %% (bound "
                      "%.0f %%); %zu facing away worst %.1f %%, mean %.1f %%\n",
                      e.name.c_str(), e.peakIrradiance, e.shLit, 100 * e.shLitWorst,
                      100 * kIblShLitBound, e.shDim, 100 * e.shDimWorst, 100 * e.shDimMean);
        out += line;
        std::snprintf(line, sizeof line, "  %-4s %10s %10s %10s  %s\n", "mip", "roughness", "worst",
                      "mean", "bound");
        out += line;
        for (const auto& m : e.mips) {
            std::snprintf(line, sizeof line, "  %-4u %10.3f %9.2f%% %9.2f%%  %s %s\n", m.mip,
                          m.linearRoughness, 100 * m.worst, 100 * m.mean,
                          m.resolved ? "worst <= 5 %" : "mean <= 2 % (lobe under two texels)",
                          m.pass() ? "ok" : "FAIL");
            out += line;
        }
    }
    std::snprintf(line, sizeof line,
                  "DFG table: worst |table - integrator| %.4f over %zu texels (bound %.2f) %s\n",
                  r.dfgWorst, r.dfgTexels, kIblDfgBound,
                  r.dfgWorst <= kIblDfgBound ? "ok" : "FAIL");
    out += line;
    return out;
}

Result<void> writeIblAccuracyReport(const IblAccuracy& r, const std::string& dir) {
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec) return fail(ErrorCode::Io, "cannot create '" + dir + "': " + ec.message());
    std::ofstream html(dir + "/index.html");
    if (!html) return fail(ErrorCode::Io, "cannot write '" + dir + "/index.html'");
    html << "<!doctype html>\n<html><head><meta charset=\"utf-8\"><title>rgraph accuracy: "
            "image-based light</title>\n"
         << "<style>body{font-family:sans-serif;background:#111;color:#ddd}table{border-collapse:"
            "collapse}td,th{padding:4px 10px;border-bottom:1px solid #333;text-align:right}"
            "td:first-child{text-align:left}img{image-rendering:pixelated;height:48px}</style>"
            "</head><body>\n<h1>The distant probe against its definitions</h1>\n<p>Relative "
            "error against integrals over every texel of the cube the filter reads. Heat maps: "
            "the six faces (+X −X +Y −Y +Z −Z) side by side, 0 (black) to the bound (yellow) "
            "and beyond.</p>\n";
    char row[640];
    for (const auto& e : r.environments) {
        const std::string shFile = e.name + "_sh.png";
        if (auto w =
                writePng(dir + "/" + shFile, golden::heatMap(e.shError, float(kIblShLitBound)));
            !w)
            return w;
        std::snprintf(row, sizeof row,
                      "<h2>%s</h2>\n<p>SH irradiance: lit directions worst %.2f %%; facing away "
                      "worst %.1f %%, mean %.1f %% <img src=\"%s\"></p>\n<table><tr><th>mip</th>"
                      "<th>linear roughness</th><th>worst</th><th>mean</th><th>bound</th><th>heat "
                      "map</th></tr>\n",
                      e.name.c_str(), 100 * e.shLitWorst, 100 * e.shDimWorst, 100 * e.shDimMean,
                      shFile.c_str());
        html << row;
        for (const auto& m : e.mips) {
            const std::string file = e.name + "_mip" + std::to_string(m.mip) + ".png";
            if (auto w =
                    writePng(dir + "/" + file, golden::heatMap(m.error, float(kIblPrefilterBound)));
                !w)
                return w;
            std::snprintf(row, sizeof row,
                          "<tr><td>%u</td><td>%.3f</td><td>%.2f %%</td><td>%.2f %%</td><td>%s "
                          "%s</td><td><img src=\"%s\"></td></tr>\n",
                          m.mip, m.linearRoughness, 100 * m.worst, 100 * m.mean,
                          m.resolved ? "worst ≤ 5 %" : "mean ≤ 2 %", m.pass() ? "ok" : "FAIL",
                          file.c_str());
            html << row;
        }
        html << "</table>\n";
    }
    std::snprintf(row, sizeof row,
                  "<p>DFG table: worst |table − integrator| %.4f over %zu texels "
                  "(bound %.2f)</p>\n",
                  r.dfgWorst, r.dfgTexels, kIblDfgBound);
    html << row << "</body></html>\n";
    if (!html) return fail(ErrorCode::Io, "cannot write '" + dir + "/index.html'");
    return {};
}

}  // namespace rg

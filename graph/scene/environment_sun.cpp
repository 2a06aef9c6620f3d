// A sun in an equirectangular environment, found, taken out and made a light (environment.h;
// seed 002 §4.9.1.1: the distant probe holds the sky, strong sources are lights of their own).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

#include <glm/geometric.hpp>

#include "environment.h"

namespace rg {

namespace {

constexpr double kPi = 3.14159265358979;
constexpr float kRealSunRadius = 0.00465f;  // radians: 0.2664°, the sun seen from the earth

double luminance(const Image& img, uint32_t x, uint32_t y) {
    const float* p = &img.pixels[img.index(x, y, 0)];
    return img.channels >= 3 ? 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2] : p[0];
}

// The exact solid angle of a texel of row y: its longitude step times the band's cos θ span.
double rowSolidAngle(const Image& img, uint32_t y) {
    const double t0 = kPi * y / img.height, t1 = kPi * (y + 1.0) / img.height;
    return 2.0 * kPi / img.width * (std::cos(t0) - std::cos(t1));
}

glm::dvec3 texelDirection(const Image& img, uint32_t x, uint32_t y) {
    return glm::dvec3(
        equirectDirection({(static_cast<float>(x) + 0.5f) / static_cast<float>(img.width),
                           (static_cast<float>(y) + 0.5f) / static_cast<float>(img.height)}));
}

}  // namespace

std::optional<EnvironmentSun> findEnvironmentSun(const Image& img) {
    if (img.width < 2 || img.height < 2 || img.pixels.empty()) return std::nullopt;
    const uint32_t w = img.width, h = img.height;
    std::vector<double> lum(size_t(w) * h);
    double total = 0.0, peak = -1.0;
    uint32_t peakIndex = 0;
    for (uint32_t y = 0; y < h; ++y) {
        const double omega = rowSolidAngle(img, y);
        for (uint32_t x = 0; x < w; ++x) {
            const size_t i = size_t(y) * w + x;
            lum[i] = std::max(luminance(img, x, y), 0.0);
            total += lum[i] * omega;
            if (lum[i] > peak) peak = lum[i], peakIndex = static_cast<uint32_t>(i);
        }
    }
    const double mean = total / (4.0 * kPi);
    if (!(mean > 0.0) || peak < kSunPeakContrast * mean) return std::nullopt;

    // The region: connected to the peak, above the hot threshold; its ring: the neighbours below it.
    const double hot = kSunHotContrast * mean;
    std::vector<uint8_t> state(lum.size(), 0);  // 1 region, 2 ring
    std::vector<uint32_t> stack{peakIndex}, region, ring;
    state[peakIndex] = 1;
    double solidAngle = 0.0;
    while (!stack.empty()) {
        const uint32_t i = stack.back();
        stack.pop_back();
        region.push_back(i);
        const uint32_t x = i % w, y = i / w;
        solidAngle += rowSolidAngle(img, y);
        if (solidAngle > kSunMaxSolidAngle) return std::nullopt;
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                const int yy = int(y) + dy;
                if ((dx == 0 && dy == 0) || yy < 0 || yy >= int(h)) continue;
                const uint32_t xx = (x + w + uint32_t(dx + 1) - 1u) % w;
                const uint32_t j = uint32_t(yy) * w + xx;
                if (state[j]) continue;
                state[j] = lum[j] > hot ? 1 : 2;
                (state[j] == 1 ? stack : ring).push_back(j);
            }
    }
    EnvironmentSun sun;
    sun.peakNits = static_cast<float>(peak);
    sun.solidAngle = static_cast<float>(solidAngle);
    // The fill: the ring's solid-angle-weighted mean radiance (continuous with the sky around it).
    glm::dvec3 fill(0.0);
    double ringOmega = 0.0;
    for (uint32_t j : ring) {
        const double omega = rowSolidAngle(img, j / w);
        const float* p = &img.pixels[img.index(j % w, j / w, 0)];
        fill += omega *
                glm::dvec3(p[0], img.channels >= 3 ? p[1] : p[0], img.channels >= 3 ? p[2] : p[0]);
        ringOmega += omega;
    }
    if (ringOmega > 0.0) fill /= ringOmega;
    // What the region holds above the fill: the sun's illuminance, its direction, its spread.
    glm::dvec3 e(0.0), centroid(0.0);
    std::vector<std::pair<glm::dvec3, double>> weights;
    for (uint32_t i : region) {
        const double omega = rowSolidAngle(img, i / w);
        const float* p = &img.pixels[img.index(i % w, i / w, 0)];
        const glm::dvec3 L(p[0], img.channels >= 3 ? p[1] : p[0], img.channels >= 3 ? p[2] : p[0]);
        const glm::dvec3 excess = glm::max(L - fill, glm::dvec3(0.0));
        e += excess * omega;
        const double y = 0.2126 * excess.x + 0.7152 * excess.y + 0.0722 * excess.z;
        const glm::dvec3 d = texelDirection(img, i % w, i / w);
        centroid += y * omega * d;
        weights.emplace_back(d, y * omega);
    }
    if (glm::length(centroid) <= 0.0) return std::nullopt;
    const glm::dvec3 toSun = glm::normalize(centroid);
    double spread = 0.0, weight = 0.0;
    for (const auto& [d, wgt] : weights) {
        const double theta = std::acos(std::clamp(glm::dot(d, toSun), -1.0, 1.0));
        spread += wgt * theta * theta;
        weight += wgt;
    }
    sun.toSun = glm::vec3(toSun);
    sun.illuminance = glm::vec3(e);
    sun.fill = glm::vec3(fill);
    sun.angularRadius = std::max(
        static_cast<float>(std::sqrt(2.0 * spread / std::max(weight, 1e-30))), kRealSunRadius);
    std::sort(region.begin(), region.end());
    sun.texels = std::move(region);
    return sun;
}

void removeEnvironmentSun(Image& img, const EnvironmentSun& sun) {
    for (uint32_t i : sun.texels) {
        const uint32_t x = i % img.width, y = i / img.width;
        if (y >= img.height) continue;
        for (uint32_t c = 0; c < std::min(img.channels, 3u); ++c)
            img.at(x, y, c) = sun.fill[static_cast<int>(c)];
    }
}

Result<std::string> takeEnvironmentSun(Scene& scene) {
    if (!scene.environment || scene.environment->kind != "hdr") return std::string();
    const Environment& env = *scene.environment;
    const bool hasSun = std::any_of(scene.lights.begin(), scene.lights.end(), [](const Light& l) {
        return l.type == LightType::Directional;
    });
    const bool taken = std::any_of(scene.lights.begin(), scene.lights.end(),
                                   [](const Light& l) { return l.fromEnvironment; });
    if (env.sun == "keep" || taken) return std::string();
    auto image = environmentImage(scene, /*keepSun=*/true);
    if (!image) return std::unexpected(image.error());
    const auto sun = findEnvironmentSun(*image);
    // The image the GPU scene and the baker will ask for, sun taken out: kept, not read again.
    if (sun) removeEnvironmentSun(*image, *sun);
    scene.environment->image = std::make_shared<const Image>(std::move(*image));
    const std::string what = "environment '" + env.name + "'";
    if (!sun) return what + ": no sun found (no compact source over 1000 x the mean)";
    const glm::vec3 s = sun->toSun;
    const double elevation = std::asin(std::clamp(double(s.y), -1.0, 1.0)) * 180.0 / kPi,
                 azimuth = std::atan2(double(s.x), double(-s.z)) * 180.0 / kPi;
    const float lux =
        0.2126f * sun->illuminance.x + 0.7152f * sun->illuminance.y + 0.0722f * sun->illuminance.z;
    char line[320];
    if (env.sun == "remove" || (env.sun == "auto" && hasSun)) {
        std::snprintf(
            line, sizeof line,
            "%s: its sun (%.4g lux, %.1f deg up, azimuth %.1f deg) taken out of the image; "
            "the scene's sun light stands for it",
            what.c_str(), double(lux), elevation, azimuth);
        return std::string(line);
    }
    Light l;
    l.name = env.name + " sun";
    l.type = LightType::Directional;
    l.direction = -s;
    l.unit = "lux";
    l.intensity = lux;
    l.color = lux > 0.0f ? sun->illuminance / lux : glm::vec3(1.0f);
    l.sunAngularRadius = sun->angularRadius;
    l.fromEnvironment = true;
    scene.lights.push_back(l);
    std::snprintf(line, sizeof line,
                  "%s: its sun taken out into light '%s': %.4g lux, %.1f deg up, azimuth %.1f deg, "
                  "angular radius %.2f deg (%u texels, %.2g sr)",
                  what.c_str(), l.name.c_str(), double(lux), elevation, azimuth,
                  double(sun->angularRadius) * 180.0 / kPi, unsigned(sun->texels.size()),
                  double(sun->solidAngle));
    return std::string(line);
}

}  // namespace rg

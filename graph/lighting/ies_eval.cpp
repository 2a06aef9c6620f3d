// IES profiles, the light side (ies.h): evaluation of the candela table (types A, B and C),
// symmetry unfolding, flux, the baked texture of lst:5 and its sampling.
#include "ies.h"

#include <algorithm>
#include <cmath>
#include <iterator>

#include <glm/geometric.hpp>

#include "core/check.h"

namespace rg {

namespace {

constexpr double kPi = 3.14159265358979323846;
// Angles closer than this (degrees, 0.36") are the same angle: a float in radians carries about
// 1e-5° of rounding (float π is 5e-6° above 180°), far inside it.
constexpr double kAngleEpsilon = 1e-4;

// Folds a horizontal angle (degrees) into the declared range by the profile's symmetry.
double foldHorizontal(const IesProfile& p, double h) {
    h = std::fmod(h, 360.0);
    if (h < 0.0) h += 360.0;
    switch (p.symmetry) {
        case IesSymmetry::Rotational:
            return p.horizontalAngles.front();
        case IesSymmetry::Quadrant:
            if (h > 180.0) h = 360.0 - h;
            if (h > 90.0) h = 180.0 - h;
            return h;
        case IesSymmetry::Bilateral:
            return h > 180.0 ? 360.0 - h : h;
        case IesSymmetry::Bilateral90:
            if (h < 90.0) return 180.0 - h;  // mirror about the 90°–270° plane
            if (h > 270.0) return 540.0 - h;
            return h;
        case IesSymmetry::None:
            return h;
    }
    return h;
}

// Index i and weight w with angles[i] ≤ x ≤ angles[i + 1] (x already inside the range).
void bracket(const std::vector<float>& angles, double x, size_t& i, double& w) {
    if (angles.size() < 2) {
        i = 0;
        w = 0.0;
        return;
    }
    const auto it =
        std::upper_bound(angles.begin(), angles.end(), x, [](double a, float b) { return a < b; });
    const size_t upper = static_cast<size_t>(std::distance(angles.begin(), it));
    i = std::min(upper == 0 ? 0 : upper - 1, angles.size() - 2);
    const double a0 = angles[i], a1 = angles[i + 1];
    w = std::clamp((x - a0) / (a1 - a0), 0.0, 1.0);
}

// Types A and B: the table's bilinear value at its own angles (h lateral, v vertical, degrees),
// mirrored onto the negative side when the table starts at 0, 0 outside it.
double evaluateAimedTable(const IesProfile& p, double h, double v) {
    const size_t nV = p.verticalAngles.size(), nH = p.horizontalAngles.size();
    if (p.mirrorHorizontal) h = std::abs(h);
    if (p.mirrorVertical) v = std::abs(v);
    if (h < p.horizontalAngles.front() - kAngleEpsilon ||
        h > p.horizontalAngles.back() + kAngleEpsilon ||
        v < p.verticalAngles.front() - kAngleEpsilon || v > p.verticalAngles.back() + kAngleEpsilon)
        return 0.0;
    size_t iv, ih;
    double wv, wh;
    bracket(p.verticalAngles,
            std::clamp<double>(v, p.verticalAngles.front(), p.verticalAngles.back()), iv, wv);
    bracket(p.horizontalAngles,
            std::clamp<double>(h, p.horizontalAngles.front(), p.horizontalAngles.back()), ih, wh);
    const size_t iv1 = std::min(iv + 1, nV - 1), ih1 = std::min(ih + 1, nH - 1);
    const auto at = [&](size_t i, size_t j) { return static_cast<double>(p.candela[i * nV + j]); };
    const double c0 = (1.0 - wv) * at(ih, iv) + wv * at(ih, iv1);
    const double c1 = (1.0 - wv) * at(ih1, iv) + wv * at(ih1, iv1);
    return (1.0 - wh) * c0 + wh * c1;
}

}  // namespace

glm::dvec2 aimedAngles(int photometricType, glm::dvec3 d) {
    constexpr double toDegrees = 180.0 / kPi;
    d = glm::normalize(d);
    if (photometricType ==
        2)  // type B: the polar axis is x; V turns the plane about it, H leaves the plane towards x
        return {std::asin(std::clamp(d.x, -1.0, 1.0)) * toDegrees,
                std::atan2(d.y, d.z) * toDegrees};
    // type A: the polar axis is y; H turns the plane about it, V leaves the plane towards y
    return {std::atan2(d.x, d.z) * toDegrees, std::asin(std::clamp(d.y, -1.0, 1.0)) * toDegrees};
}

double evaluateDegrees(const IesProfile& p, double horizontalDegrees, double verticalDegrees) {
    const size_t nV = p.verticalAngles.size(), nH = p.horizontalAngles.size();
    if (nV == 0 || nH == 0 || p.candela.size() != nV * nH) return 0.0;
    if (p.photometricType == 2 || p.photometricType == 3) {
        // The light-space direction of these type C angles, then the table's own angles.
        constexpr double toRadians = kPi / 180.0;
        const double h = horizontalDegrees * toRadians, v = verticalDegrees * toRadians;
        const glm::dvec2 aimed = aimedAngles(
            p.photometricType, {std::sin(v) * std::cos(h), std::sin(v) * std::sin(h), std::cos(v)});
        return evaluateAimedTable(p, aimed.x, aimed.y);
    }
    // Outside the measured vertical range the luminaire sends nothing (e.g. above a downlight).
    if (verticalDegrees < p.verticalAngles.front() - kAngleEpsilon ||
        verticalDegrees > p.verticalAngles.back() + kAngleEpsilon)
        return 0.0;
    size_t iv;
    double wv;
    bracket(p.verticalAngles,
            std::clamp<double>(verticalDegrees, p.verticalAngles.front(), p.verticalAngles.back()),
            iv, wv);
    const size_t iv1 = std::min(iv + 1, nV - 1);

    size_t ih0 = 0, ih1 = 0;
    double wh = 0.0;
    const double h = foldHorizontal(p, horizontalDegrees);
    if (nH > 1) {
        const double last = p.horizontalAngles.back();
        if (p.symmetry == IesSymmetry::None && h > last) {
            // The gap between the last angle and 360° closes on the 0° column.
            ih0 = nH - 1;
            ih1 = 0;
            wh = last < 360.0 ? (h - last) / (360.0 - last) : 0.0;
        } else {
            bracket(p.horizontalAngles, std::clamp<double>(h, p.horizontalAngles.front(), last),
                    ih0, wh);
            ih1 = ih0 + 1;
        }
    }
    const auto at = [&](size_t ih, size_t v) {
        return static_cast<double>(p.candela[ih * nV + v]);
    };
    // (1 − w)·a + w·b returns a and b exactly at w = 0 and w = 1, i.e. at the table's angles.
    const double c0 = (1.0 - wv) * at(ih0, iv) + wv * at(ih0, iv1);
    const double c1 = (1.0 - wv) * at(ih1, iv) + wv * at(ih1, iv1);
    return (1.0 - wh) * c0 + wh * c1;
}

float evaluate(const IesProfile& profile, float theta, float phi) {
    const double toDegrees = 180.0 / kPi;
    return static_cast<float>(evaluateDegrees(profile, theta * toDegrees, phi * toDegrees));
}

IesProfile expandSymmetry(const IesProfile& p) {
    IesProfile out = p;
    if (p.photometricType != 1) return out;  // types A and B mirror in evaluation
    if (p.symmetry == IesSymmetry::None && !p.horizontalAngles.empty() &&
        p.horizontalAngles.back() == 360.0f)
        return out;
    // Every image of a table angle under the symmetry, plus both ends of the circle.
    std::vector<double> hs = {0.0, 360.0};
    for (const float a : p.horizontalAngles) {
        const double x = a;
        switch (p.symmetry) {
            case IesSymmetry::Rotational:
                break;
            case IesSymmetry::Quadrant:
                hs.insert(hs.end(), {x, 180.0 - x, 180.0 + x, 360.0 - x});
                break;
            case IesSymmetry::Bilateral:
                hs.insert(hs.end(), {x, 360.0 - x});
                break;
            case IesSymmetry::Bilateral90:
                hs.insert(hs.end(), {x, x <= 180.0 ? 180.0 - x : 540.0 - x});
                break;  // 180° − x mod 360°
            case IesSymmetry::None:
                hs.push_back(x);
                break;
        }
    }
    std::erase_if(hs, [](double x) { return x < 0.0 || x > 360.0; });
    std::sort(hs.begin(), hs.end());
    hs.erase(std::unique(hs.begin(), hs.end(),
                         [](double a, double b) { return std::abs(a - b) < kAngleEpsilon; }),
             hs.end());

    out.horizontalAngles.assign(hs.begin(), hs.end());
    out.candela.clear();
    out.candela.reserve(hs.size() * p.verticalAngles.size());
    for (const double h : hs)
        for (const float v : p.verticalAngles)
            out.candela.push_back(static_cast<float>(evaluateDegrees(p, h, v)));
    out.symmetry = IesSymmetry::None;
    return out;
}

double integrateLumens(const IesProfile& profile, int steps) {
    RG_CHECK(steps > 0) << "integrateLumens needs at least one step, got " << steps;
    // ∫∫ I(h, v) sin v dv dh over v ∈ [0, π], h ∈ [0, 2π), midpoint rule.
    const double dv = kPi / steps, dh = 2.0 * kPi / steps;
    double sum = 0.0;
    for (int i = 0; i < steps; ++i) {
        const double v = (i + 0.5) * dv;
        double ring = 0.0;
        for (int j = 0; j < steps; ++j)
            ring += evaluateDegrees(profile, (j + 0.5) * dh * 180.0 / kPi, v * 180.0 / kPi);
        sum += ring * std::sin(v);
    }
    return sum * dv * dh;
}

IesTexture bakeIes(const IesProfile& profile, uint32_t width, uint32_t height) {
    RG_CHECK(width > 0 && height > 0)
        << "an IES texture needs a positive size, got " << width << " x " << height;
    IesTexture tex;
    tex.width = width;
    tex.height = height;
    tex.maxCandela = profile.maxCandela;
    tex.texels.resize(static_cast<size_t>(width) * height);
    // seed 000 §4.5: store I / I_max so the texture is both a profile and a mask (eq:27).
    const double scale = profile.maxCandela > 0.0f ? 1.0 / profile.maxCandela : 0.0;
    for (uint32_t j = 0; j < height; ++j) {
        const double cosPhi = 2.0 * (j + 0.5) / height - 1.0;  // lst:5: v = cos φ · 0.5 + 0.5
        const double vertical = std::acos(cosPhi) * 180.0 / kPi;
        for (uint32_t i = 0; i < width; ++i) {
            const double horizontal = 360.0 * (i + 0.5) / width;  // lst:5: u = θ / 2π
            tex.texels[static_cast<size_t>(j) * width + i] = static_cast<float>(
                std::min(1.0, evaluateDegrees(profile, horizontal, vertical) * scale));
        }
    }
    return tex;
}

glm::vec2 iesTexCoord(glm::vec3 d) {
    // seed 000 lst:5: cos φ from z scaled from [-1, 1] to [0, 1]; θ = atan2(y, x) / 2π.
    const float phiCoord = d.z * 0.5f + 0.5f;
    const float theta = std::atan2(d.y, d.x);
    const float thetaCoord = theta * static_cast<float>(1.0 / (2.0 * kPi));
    return {thetaCoord, phiCoord};
}

float sampleIesTexture(const IesTexture& t, glm::vec2 uv) {
    if (t.width == 0 || t.height == 0) return 0.0f;
    const double x = static_cast<double>(uv.x) * t.width - 0.5;
    const double y = static_cast<double>(uv.y) * t.height - 0.5;
    const double fx0 = std::floor(x), fy0 = std::floor(y);
    const double wx = x - fx0, wy = y - fy0;
    const auto W = static_cast<int64_t>(t.width), Hh = static_cast<int64_t>(t.height);
    const auto wrap = [&](int64_t i) { return ((i % W) + W) % W; };  // repeat
    const auto clampRow = [&](int64_t j) {
        return std::clamp<int64_t>(j, 0, Hh - 1);
    };  // clamp to edge
    const int64_t i0 = wrap(static_cast<int64_t>(fx0)), i1 = wrap(static_cast<int64_t>(fx0) + 1);
    const int64_t j0 = clampRow(static_cast<int64_t>(fy0)),
                  j1 = clampRow(static_cast<int64_t>(fy0) + 1);
    const auto at = [&](int64_t i, int64_t j) {
        return static_cast<double>(t.texels[static_cast<size_t>(j * W + i)]);
    };
    const double top = (1.0 - wx) * at(i0, j0) + wx * at(i1, j0);
    const double bottom = (1.0 - wx) * at(i0, j1) + wx * at(i1, j1);
    return static_cast<float>((1.0 - wy) * top + wy * bottom);
}

float getIESProfileAttenuation(glm::vec3 L, const glm::mat3& worldToLight,
                               const IesTexture& texture) {
    // seed 000 lst:5: the sample direction goes from the light to the point, in light space.
    const glm::vec3 iesSampleDirection = worldToLight * -L;
    return sampleIesTexture(texture, iesTexCoord(iesSampleDirection));
}

}  // namespace rg

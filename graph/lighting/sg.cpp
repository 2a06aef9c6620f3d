#include "sg.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace rg::lighting {

namespace {
constexpr float kPi = 3.14159265358979f;
}

glm::vec3 evaluate(const SphericalGaussian& g, const glm::vec3& x) {
    return g.amplitude * std::exp(g.sharpness * (glm::dot(g.axis, x) - 1.0f));
}

glm::vec3 integral(const SphericalGaussian& g) {
    // −expm1(−2λ) = 1 − e^{−2λ}, exact for small λ too.
    return g.amplitude * (2.0f * kPi / g.sharpness * static_cast<float>(-std::expm1(-2.0 * g.sharpness)));
}

SphericalGaussian product(const SphericalGaussian& a, const SphericalGaussian& b) {
    const glm::vec3 um = a.sharpness * a.axis + b.sharpness * b.axis;
    const float lm = glm::length(um);
    SphericalGaussian out;
    out.sharpness = lm;
    out.axis = lm > 0.0f ? um / lm : a.axis;
    out.amplitude = a.amplitude * b.amplitude * std::exp(lm - a.sharpness - b.sharpness);
    return out;
}

glm::vec3 innerProduct(const SphericalGaussian& a, const SphericalGaussian& b) {
    const SphericalGaussian p = product(a, b);
    // λm → 0 (opposite lobes of equal sharpness): the product is the constant A, integral 4π A.
    if (p.sharpness < 1e-4f) return p.amplitude * (4.0f * kPi);
    return integral(p);
}

SphericalGaussian cosineLobe(const glm::vec3& n) { return SphericalGaussian{glm::normalize(n), 2.133f, glm::vec3(1.17f)}; }

glm::vec3 irradiance(const SphericalGaussian& radiance, const glm::vec3& n) { return innerProduct(radiance, cosineLobe(n)); }

std::vector<glm::vec3> goldenSpiralAxes(int n, bool hemisphere) {
    std::vector<glm::vec3> out;
    const float goldenAngle = kPi * (3.0f - std::sqrt(5.0f));
    for (int i = 0; i < n; ++i) {
        // Sphere: z from 1 − 1/n to −1 + 1/n; hemisphere: z from 1 − 1/(2n) to 1/(2n).
        const float t = (static_cast<float>(i) + 0.5f) / static_cast<float>(n);
        const float z = hemisphere ? 1.0f - t : 1.0f - 2.0f * t;
        const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
        const float phi = goldenAngle * static_cast<float>(i);
        out.emplace_back(r * std::cos(phi), r * std::sin(phi), z);
    }
    return out;
}

float basisSharpness(const std::vector<glm::vec3>& axes) {
    // The mean angle from each axis to its nearest neighbour.
    float sum = 0.0f;
    for (size_t i = 0; i < axes.size(); ++i) {
        float best = -1.0f;
        for (size_t j = 0; j < axes.size(); ++j)
            if (j != i) best = std::max(best, glm::dot(axes[i], axes[j]));
        sum += std::acos(std::clamp(best, -1.0f, 1.0f));
    }
    const float theta = axes.size() > 1 ? sum / static_cast<float>(axes.size()) : kPi;
    return std::log(2.0f) / (1.0f - std::cos(0.5f * theta));
}

}  // namespace rg::lighting

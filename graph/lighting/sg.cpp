#include "sg.h"

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

}  // namespace rg::lighting

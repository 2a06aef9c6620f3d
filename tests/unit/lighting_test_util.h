// What the CPU lighting tests (tests/unit/test_light_units.cpp, test_brdf.cpp,
// test_area_lights.cpp, test_ies.cpp) share: π, degrees and a brute-force cap illuminance.
#pragma once

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

namespace rg::test {

inline constexpr double kPi = 3.14159265358979323846;

inline double deg(double d) { return d * kPi / 180.0; }

// ---- Reference integrals (brute force, independent of the formulas under test) ----------------

// ∫ max(n·l, 0) dω over a cone of half-angle σ around the direction at angle θ from n = +z: the
// illuminance of a uniform light of luminance 1 that subtends that cone (a sphere, or a disk facing
// the point). Equal-area midpoint grid.
inline double capIlluminanceReference(double cosTheta, double sinSigma, int n = 1000) {
    const double sinTheta = std::sqrt(std::max(0.0, 1.0 - cosTheta * cosTheta));
    const glm::dvec3 axis{sinTheta, 0.0, cosTheta}, t1{cosTheta, 0.0, -sinTheta}, t2{0.0, 1.0, 0.0};
    const double sigma = std::asin(sinSigma);
    const double oneMinusCos = 2.0 * std::sin(sigma / 2) * std::sin(sigma / 2);
    double sum = 0.0;
    for (int i = 0; i < n; ++i) {
        const double cosA = 1.0 - oneMinusCos * (i + 0.5) / n,
                     sinA = std::sqrt(std::max(0.0, 1.0 - cosA * cosA));
        for (int j = 0; j < n; ++j) {
            const double b = 2.0 * kPi * (j + 0.5) / n;
            const glm::dvec3 l = cosA * axis + sinA * (std::cos(b) * t1 + std::sin(b) * t2);
            sum += std::max(l.z, 0.0);
        }
    }
    return sum * oneMinusCos * 2.0 * kPi / (static_cast<double>(n) * n);
}

}  // namespace rg::test

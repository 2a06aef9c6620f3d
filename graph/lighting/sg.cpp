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
    return g.amplitude *
           (2.0f * kPi / g.sharpness * static_cast<float>(-std::expm1(-2.0 * g.sharpness)));
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

SphericalGaussian cosineLobe(const glm::vec3& n) {
    return SphericalGaussian{glm::normalize(n), 2.133f, glm::vec3(1.17f)};
}

glm::vec3 irradiance(const SphericalGaussian& radiance, const glm::vec3& n) {
    return innerProduct(radiance, cosineLobe(n));
}

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

namespace {

// Least squares on the passive set P only: minimise |A_P z - b| by the normal equations
// (A_Pᵀ A_P) z = A_Pᵀ b, Cholesky-factored (the basis has at most a few dozen lobes).
std::vector<double> solvePassive(const std::vector<double>& ata, const std::vector<double>& atb,
                                 const std::vector<int>& passive, size_t n) {
    const size_t m = passive.size();
    std::vector<double> l(m * m, 0.0), z(n, 0.0), y(m, 0.0);
    for (size_t i = 0; i < m; ++i)
        for (size_t j = 0; j <= i; ++j) {
            double sum = ata[size_t(passive[i]) * n + size_t(passive[j])];
            for (size_t k = 0; k < j; ++k) sum -= l[i * m + k] * l[j * m + k];
            if (i == j)
                l[i * m + i] = std::sqrt(std::max(sum, 1e-300));
            else
                l[i * m + j] = sum / l[j * m + j];
        }
    for (size_t i = 0; i < m; ++i) {
        double sum = atb[size_t(passive[i])];
        for (size_t k = 0; k < i; ++k) sum -= l[i * m + k] * y[k];
        y[i] = sum / l[i * m + i];
    }
    for (size_t i = m; i-- > 0;) {
        double sum = y[i];
        for (size_t k = i + 1; k < m; ++k) sum -= l[k * m + i] * z[size_t(passive[k])];
        z[size_t(passive[i])] = sum / l[i * m + i];
    }
    return z;
}

// Lawson-Hanson NNLS on the normal equations: min |Ax - b|², x ≥ 0.
std::vector<double> nnls(const std::vector<double>& ata, const std::vector<double>& atb, size_t n) {
    std::vector<double> x(n, 0.0);
    std::vector<bool> inP(n, false);
    auto gradient = [&](size_t j) {  // wⱼ = (Aᵀ(b − Ax))ⱼ
        double w = atb[j];
        for (size_t k = 0; k < n; ++k) w -= ata[j * n + k] * x[k];
        return w;
    };
    for (int outer = 0; outer < 3 * static_cast<int>(n) + 10; ++outer) {
        int best = -1;
        double bestW = 1e-12;
        for (size_t j = 0; j < n; ++j)
            if (!inP[j] && gradient(j) > bestW) bestW = gradient(j), best = static_cast<int>(j);
        if (best < 0) break;  // KKT: every free coefficient's gradient ≤ 0
        inP[size_t(best)] = true;
        for (int inner = 0; inner < 3 * static_cast<int>(n) + 10; ++inner) {
            std::vector<int> passive;
            for (size_t j = 0; j < n; ++j)
                if (inP[j]) passive.push_back(static_cast<int>(j));
            std::vector<double> z = solvePassive(ata, atb, passive, n);
            bool feasible = true;
            for (int j : passive) feasible = feasible && z[size_t(j)] > 0.0;
            if (feasible) {
                x = z;
                break;
            }
            // Step towards z until a coefficient reaches 0; it leaves the passive set.
            double alpha = 1.0;
            for (int j : passive)
                if (z[size_t(j)] <= 0.0)
                    alpha = std::min(alpha, x[size_t(j)] / (x[size_t(j)] - z[size_t(j)]));
            for (size_t j = 0; j < n; ++j) {
                x[j] += alpha * (z[j] - x[j]);
                if (inP[j] && x[j] <= 1e-12) {
                    x[j] = 0.0;
                    inP[j] = false;
                }
            }
        }
    }
    return x;
}

}  // namespace

std::vector<glm::vec3> fitNonNegative(const std::vector<double>& gram,
                                      const std::vector<glm::dvec3>& projections) {
    const size_t n = projections.size();
    std::vector<glm::vec3> out(n, glm::vec3(0.0f));
    std::vector<double> atb(n);
    for (int c = 0; c < 3; ++c) {
        for (size_t k = 0; k < n; ++k) atb[k] = projections[k][c];
        const std::vector<double> x = nnls(gram, atb, n);
        for (size_t k = 0; k < n; ++k) out[k][c] = static_cast<float>(x[k]);
    }
    return out;
}

std::vector<glm::vec3> fitNonNegative(const std::vector<glm::vec3>& axes, float sharpness,
                                      const std::vector<glm::vec3>& directions,
                                      const std::vector<glm::vec3>& radiance) {
    const size_t n = axes.size();
    std::vector<double> ata(n * n, 0.0);
    std::vector<glm::dvec3> atb(n, glm::dvec3(0.0));
    std::vector<double> row(n);
    for (size_t s = 0; s < directions.size(); ++s) {
        for (size_t k = 0; k < n; ++k)
            row[k] = std::exp(double(sharpness) * (double(glm::dot(axes[k], directions[s])) - 1.0));
        for (size_t i = 0; i < n; ++i) {
            for (size_t j = 0; j < n; ++j) ata[i * n + j] += row[i] * row[j];
            atb[i] += row[i] * glm::dvec3(radiance[s]);
        }
    }
    return fitNonNegative(ata, atb);
}

std::vector<double> basisGram(const std::vector<glm::vec3>& axes, float sharpness,
                              bool hemisphere) {
    // Quadrature over 2^16 golden-spiral directions (each 4π / count of solid angle); the
    // hemisphere keeps those with z > 0. Lobes this wide vary slowly at that spacing (< 1e-4).
    const size_t n = axes.size();
    const std::vector<glm::vec3> dirs = goldenSpiralAxes(1 << 16);
    const double w = 4.0 * double(kPi) / double(dirs.size());
    std::vector<double> gram(n * n, 0.0), row(n);
    for (const auto& d : dirs) {
        if (hemisphere && d.z <= 0.0f) continue;
        for (size_t k = 0; k < n; ++k)
            row[k] = std::exp(double(sharpness) * (double(glm::dot(axes[k], d)) - 1.0));
        for (size_t i = 0; i < n; ++i)
            for (size_t j = 0; j < n; ++j) gram[i * n + j] += w * row[i] * row[j];
    }
    return gram;
}

glm::vec3 evaluateBasis(const std::vector<glm::vec3>& axes, float sharpness,
                        const std::vector<glm::vec3>& amplitudes, const glm::vec3& x) {
    glm::vec3 sum(0.0f);
    for (size_t k = 0; k < axes.size(); ++k)
        sum += amplitudes[k] * std::exp(sharpness * (glm::dot(axes[k], x) - 1.0f));
    return sum;
}

}  // namespace rg::lighting

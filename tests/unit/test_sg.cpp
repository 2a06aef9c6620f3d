// Spherical Gaussians (graph/lighting/sg.h; seed 003): the closed forms against numerical
// integration over the sphere (a 1024 x 512 midpoint grid in (φ, cos θ), exact in solid angle).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>

#include <glm/geometric.hpp>

#include "lighting/sg.h"

using rg::lighting::SphericalGaussian;

namespace {

constexpr double kPi = 3.14159265358979323846;

// ∫ f dω over the sphere: uniform in φ and in cos θ, so every cell has the same solid angle.
double sphereIntegral(const std::function<double(const glm::vec3&)>& f) {
    const int nPhi = 1024, nZ = 512;
    double sum = 0.0;
    for (int j = 0; j < nZ; ++j) {
        const double z = -1.0 + (j + 0.5) * 2.0 / nZ, r = std::sqrt(std::max(0.0, 1.0 - z * z));
        for (int i = 0; i < nPhi; ++i) {
            const double phi = (i + 0.5) * 2.0 * kPi / nPhi;
            sum += f(glm::vec3(float(r * std::cos(phi)), float(r * std::sin(phi)), float(z)));
        }
    }
    return sum * 4.0 * kPi / (double(nPhi) * nZ);
}

SphericalGaussian sg(glm::vec3 axis, float sharpness, float amplitude) {
    return SphericalGaussian{glm::normalize(axis), sharpness, glm::vec3(amplitude)};
}

}  // namespace

TEST(SphericalGaussian, IntegralIsTheClosedForm) {
    // 2π A / λ (1 − e^{−2λ}) for wide and sharp lobes.
    for (float lambda : {0.05f, 0.5f, 2.0f, 8.0f, 32.0f}) {
        const SphericalGaussian g = sg({0.3f, -0.2f, 0.9f}, lambda, 1.7f);
        const double numeric = sphereIntegral([&](const glm::vec3& x) { return double(rg::lighting::evaluate(g, x).x); });
        EXPECT_NEAR(rg::lighting::integral(g).x / numeric, 1.0, 1e-3) << "λ " << lambda;
    }
}

TEST(SphericalGaussian, ProductIsAnSgAndItsIntegralTheInnerProduct) {
    // The product of two SGs evaluates to the same values as the two multiplied, everywhere; its
    // integral (the inner product) matches numerical integration of G1 G2.
    const SphericalGaussian a = sg({1, 0, 0.2f}, 3.0f, 2.0f), b = sg({0.4f, 1, 0}, 5.0f, 0.5f);
    const SphericalGaussian p = rg::lighting::product(a, b);
    for (const glm::vec3 x : {glm::vec3(1, 0, 0), glm::normalize(glm::vec3(1, 1, 0)), glm::vec3(0, 0, -1), glm::normalize(glm::vec3(-1, 2, 3))})
        EXPECT_NEAR(rg::lighting::evaluate(p, x).x, rg::lighting::evaluate(a, x).x * rg::lighting::evaluate(b, x).x,
                    1e-5 * (1.0 + rg::lighting::evaluate(a, x).x * rg::lighting::evaluate(b, x).x));
    const double numeric =
        sphereIntegral([&](const glm::vec3& x) { return double(rg::lighting::evaluate(a, x).x) * rg::lighting::evaluate(b, x).x; });
    EXPECT_NEAR(rg::lighting::innerProduct(a, b).x / numeric, 1.0, 1e-3);
}

TEST(SphericalGaussian, IrradianceThroughTheCosineLobeSgAgainstNumericalIntegration) {
    // ∫ L(x) max(0, n·x) dω for radiance SGs of several sharpnesses and angles to the normal,
    // against the cosine-lobe-as-SG inner product. Errors relative to the irradiance at normal
    // incidence of the same lobe (what a lightmap texel's brightness is judged against).
    double worst = 0.0, sum = 0.0;
    int count = 0;
    const glm::vec3 n(0, 0, 1);
    for (float lambda : {1.0f, 4.0f, 16.0f}) {
        double normalIncidence = 0.0;
        for (float angle : {0.0f, 30.0f, 60.0f, 90.0f, 120.0f}) {
            const float t = angle * float(kPi) / 180.0f;
            const SphericalGaussian g = sg({std::sin(t), 0, std::cos(t)}, lambda, 1.0f);
            const double numeric = sphereIntegral(
                [&](const glm::vec3& x) { return double(rg::lighting::evaluate(g, x).x) * std::max(0.0, double(glm::dot(n, x))); });
            if (angle == 0.0f) normalIncidence = numeric;
            const double error = std::abs(rg::lighting::irradiance(g, n).x - numeric) / normalIncidence;
            worst = std::max(worst, error);
            sum += error;
            ++count;
        }
    }
    std::printf("SG irradiance via the cosine-lobe SG: mean error %.2f %%, worst %.2f %% of the normal-incidence irradiance\n",
                100.0 * sum / count, 100.0 * worst);
    EXPECT_LT(sum / count, 0.06);
    EXPECT_LT(worst, 0.15);
}

TEST(SphericalGaussian, GoldenSpiralBasisCoversTheSphereWithoutGapsOrBlur) {
    // The seed's fixed basis for N = 5, 6, 9, 12: unit axes on the golden-ratio spiral, and the
    // sharpness at which each lobe is one half at half the mean neighbour angle. With it the sum
    // of the N unit lobes stays within a factor of its mean everywhere (no gaps), and one lobe
    // keeps most of its energy near its axis (not over-blurred: it is still a direction).
    for (int n : {5, 6, 9, 12}) {
        const auto axes = rg::lighting::goldenSpiralAxes(n);
        ASSERT_EQ(axes.size(), size_t(n));
        for (const auto& a : axes) EXPECT_NEAR(glm::length(a), 1.0f, 1e-5f);
        const float lambda = rg::lighting::basisSharpness(axes);
        double lo = 1e30, hi = 0.0, mean = 0.0;
        int samples = 0;
        for (int j = 0; j < 64; ++j)
            for (int i = 0; i < 128; ++i) {
                const double z = -1.0 + (j + 0.5) / 32.0, r = std::sqrt(std::max(0.0, 1.0 - z * z)), phi = (i + 0.5) * 2.0 * kPi / 128;
                const glm::vec3 x(float(r * std::cos(phi)), float(r * std::sin(phi)), float(z));
                double sum = 0.0;
                for (const auto& a : axes) sum += rg::lighting::evaluate(SphericalGaussian{a, lambda, glm::vec3(1.0f)}, x).x;
                lo = std::min(lo, sum);
                hi = std::max(hi, sum);
                mean += sum;
                ++samples;
            }
        mean /= samples;
        // The share of one lobe's integral within the mean neighbour angle of its axis.
        const SphericalGaussian one{axes[0], lambda, glm::vec3(1.0f)};
        const double total = rg::lighting::integral(one).x;
        double cosMean = 0.0;
        for (size_t i = 1; i < axes.size(); ++i) cosMean = std::max(cosMean, double(glm::dot(axes[0], axes[i])));
        const double near =
            sphereIntegral([&](const glm::vec3& x) { return glm::dot(x, axes[0]) >= cosMean ? double(rg::lighting::evaluate(one, x).x) : 0.0; });
        std::printf("N = %2d: sharpness %.2f, lobe sum %.2f .. %.2f (mean %.2f), %.0f %% of a lobe within its nearest neighbour's angle\n", n,
                    lambda, lo, hi, mean, 100.0 * near / total);
        EXPECT_GT(lo / mean, 0.5) << n;   // no gap: nowhere below half the mean
        EXPECT_LT(hi / mean, 1.6) << n;   // nor a peak of one lobe standing out
        EXPECT_GT(near / total, 0.5) << n;  // most of a lobe stays near its axis
    }
}

// Area light illuminance on the CPU against brute-force integrals: sphere, disk and sun (seed 000
// lst:6–lst:10), rectangle and tube (seed 002 §4.7.2.5–§4.7.2.6). No GPU.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "core/light_units.h"
#include "lighting/area_lights.h"
#include "lighting/punctual.h"
#include "lighting_test_util.h"

using namespace rg;
using namespace rg::test;

namespace {

// ∫ over an emitting surface of max(n·l, 0) max(n_a·−l, 0) / d² dA (eq:30/eq:35 with L = 1) for
// surface samples (position, normal, area). Convex emitters only (back faces are culled).
struct SurfaceSample {
    glm::dvec3 p, n;
    double area;
};
template <class Samples>
double surfaceIlluminanceReference(const glm::dvec3& x, const glm::dvec3& normal,
                                   const Samples& forEachSample) {
    double sum = 0.0;
    forEachSample([&](const SurfaceSample& s) {
        const glm::dvec3 d = s.p - x;
        const double dist2 = glm::dot(d, d);
        const glm::dvec3 l = d / std::sqrt(dist2);
        sum +=
            std::max(glm::dot(normal, l), 0.0) * std::max(glm::dot(s.n, -l), 0.0) / dist2 * s.area;
    });
    return sum;
}

}  // namespace

// =============================================================================================
// Sphere, disk, sun (seed 000 lst:6–lst:10)
// =============================================================================================

TEST(SphereLight, MatchesTheIntegralWithAndWithoutTheHorizon) {
    for (double rOverD : {0.05, 0.3, 0.7, 0.95}) {
        const double d = 1.0, r = rOverD * d;
        const double sinSigma = r / d;
        for (double cosTheta : {1.0, 0.8, 0.5, 0.2, 0.0, -0.2, -0.5, -0.9}) {
            const double reference = capIlluminanceReference(cosTheta, sinSigma, 600);
            const double scale = kPi * sinSigma * sinSigma;  // the facing illuminance
            EXPECT_NEAR(lighting::illuminanceSphereOrDisk(cosTheta, sinSigma * sinSigma), reference,
                        1e-4 * scale)
                << "lst:10, r/d " << rOverD << " cos " << cosTheta;
            EXPECT_NEAR(lighting::sphereIlluminanceTilted(r, d, cosTheta), reference, 1e-4 * scale)
                << "lst:7 tilted, r/d " << rOverD << " cos " << cosTheta;
            // lst:7 without the horizon is right only while the whole sphere is above it.
            const double noHorizon = lighting::sphereIlluminanceAboveHorizon(r, d * d, cosTheta);
            if (cosTheta > sinSigma) {
                EXPECT_NEAR(noHorizon, reference, 1e-4 * scale);
            } else if (cosTheta < sinSigma * 0.99 && cosTheta > -sinSigma * 0.99) {
                EXPECT_LT(noHorizon, reference - 1e-3 * scale)
                    << "no horizon handling loses the wrapped light";
            }
        }
    }
}

TEST(SphereLight, Listing7AsPrintedHasATypoInItsLastTerm) {
    // lst:7 prints atan(sin β + sqrt(1 − y²) / x); lst:10's form, atan(sin β · sqrt(1 − y²) / x), is
    // the one that matches the integral (previous test). The printed one is visibly off.
    const double h = 1.0 / 0.7, cosBeta = 0.2, beta = std::acos(cosBeta);
    const double x = std::sqrt(h * h - 1), y = -x / std::tan(beta);
    const double printed =
        kPi * ((1 / (kPi * h * h)) *
                   (cosBeta * std::acos(y) - x * std::sin(beta) * std::sqrt(1 - y * y)) +
               (1 / kPi) * std::atan(std::sin(beta) + std::sqrt(1 - y * y) / x));
    const double reference = capIlluminanceReference(cosBeta, 0.7, 600);
    EXPECT_NEAR(lighting::sphereIlluminanceTilted(0.7, 1.0, cosBeta), reference, 1e-4);
    EXPECT_GT(std::abs(printed - reference), 0.1 * reference);
}

TEST(SphereLight, ApproachesThePointLightAsItShrinks) {
    // Sphere of fixed power at fixed distance: E → Φ / (4π d²) ⟨n·l⟩ (eq:19, eq:38) as r/d → 0, also
    // around the horizon where the sphere's light wraps.
    const double phi = 1000.0, d = 3.0;
    const double ePerp = phi / (4 * kPi * d * d);
    double previousError = 1e30;
    for (double rOverD : {0.5, 0.2, 0.05, 0.01, 0.001}) {
        const double r = rOverD * d;
        const double L = lighting::sphereLuminanceFromLumens(phi, r);
        double worst = 0.0;
        for (double c = -0.6; c <= 0.6; c += 0.01) {
            const double sphere = L * lighting::illuminanceSphereOrDisk(c, rOverD * rOverD);
            const double point = ePerp * std::max(c, 0.0);
            worst = std::max(worst, std::abs(sphere - point));
        }
        EXPECT_LT(worst, previousError) << "r/d " << rOverD;
        previousError = worst;
    }
    EXPECT_LT(previousError, 1e-3 * ePerp);
}

TEST(SphereLight, HorizonFormulaIsNonNegativeAndContinuous) {
    for (double sinSigmaSqr : {1e-4, 0.01, 0.25, 0.81, 0.9999}) {
        const double step = 1e-4;
        double previous = lighting::illuminanceSphereOrDisk(-1.0, sinSigmaSqr);
        EXPECT_GE(previous, 0.0);
        double biggestJump = 0.0;
        for (double c = -1.0 + step; c <= 1.0 + 1e-12; c += step) {
            const double e = lighting::illuminanceSphereOrDisk(std::min(c, 1.0), sinSigmaSqr);
            EXPECT_GE(e, 0.0) << "sin²σ " << sinSigmaSqr << " cos " << c;
            biggestJump = std::max(biggestJump, std::abs(e - previous));
            previous = e;
        }
        // The slope is at most π sin²σ (the facing branch); nothing jumps beyond that.
        EXPECT_LT(biggestJump, 1.01 * kPi * sinSigmaSqr * step + 1e-9) << "sin²σ " << sinSigmaSqr;
        // Both branches meet where the sphere touches the horizon (cos θ = sin σ), and at 0 the
        // wrapped light is still there.
        const double edge = std::sqrt(sinSigmaSqr);
        EXPECT_NEAR(lighting::illuminanceSphereOrDisk(edge * (1 + 1e-9), sinSigmaSqr),
                    lighting::illuminanceSphereOrDisk(edge * (1 - 1e-9), sinSigmaSqr), 1e-7);
        EXPECT_GT(lighting::illuminanceSphereOrDisk(0.0, sinSigmaSqr), 0.0);
        EXPECT_EQ(lighting::illuminanceSphereOrDisk(-edge - 1e-3, sinSigmaSqr), 0.0);
    }
    // A point inside the light gets nothing (its surface emits outwards, as the reference mode
    // integrates it); just outside, lst:10 with its clamps gives almost the whole hemisphere.
    EXPECT_EQ(lighting::sphereIlluminance(1.0, 0.25, 1.0), 0.0);
    EXPECT_NEAR(lighting::sphereIlluminance(1.0, 1.0001, 1.0), kPi, 0.01);
}

TEST(DiskLight, HorizonFormulasAgreeWithEachOtherAndTheIntegral) {
    for (double rOverD : {0.1, 0.5, 1.0, 3.0}) {
        const double d = 1.0, r = rOverD * d;
        const double sinSigmaSqr = r * r / (r * r + d * d);
        for (double cosTheta : {1.0, 0.7, 0.3, 0.05, 0.0, -0.3, -0.6, -0.95}) {
            const double reference = capIlluminanceReference(cosTheta, std::sqrt(sinSigmaSqr), 600);
            const double scale = kPi * sinSigmaSqr;
            // A disk facing the point (cosLight = 1): lst:8 "almost exact" and lst:10 are exact.
            EXPECT_NEAR(lighting::diskIlluminanceHorizon(r, d, cosTheta, 1.0), reference,
                        1e-4 * scale)
                << "lst:8, r/d " << rOverD << " cos " << cosTheta;
            if (rOverD <= 1.0) {  // lst:10 keeps the point at least r away (below)
                EXPECT_NEAR(lighting::diskIlluminance(r, d * d, cosTheta, 1.0), reference,
                            1e-4 * scale)
                    << "lst:10, r/d " << rOverD << " cos " << cosTheta;
                // The disk's own orientation scales both the same way.
                EXPECT_NEAR(lighting::diskIlluminance(r, d * d, cosTheta, 0.5),
                            0.5 * lighting::diskIlluminanceHorizon(r, d, cosTheta, 1.0), 1e-9);
            }
        }
        // Without the horizon (lst:8, Coombe): eq:39's value while the disk is above the horizon.
        EXPECT_NEAR(lighting::diskIlluminanceAboveHorizon(r, d * d, 1.0, 1.0), kPi * sinSigmaSqr,
                    1e-12);
        EXPECT_EQ(lighting::diskIlluminanceAboveHorizon(r, d * d, -0.1, 1.0), 0.0);
    }
    // lst:10's disk never lets the point come closer than r: at d < r it lights like d = r.
    EXPECT_NEAR(lighting::diskIlluminance(1.0, 0.0, 1.0, 1.0), kPi * 0.5, 1e-12);
    EXPECT_NEAR(lighting::diskIlluminance(3.0, 1.0, 0.4, 1.0),
                lighting::diskIlluminance(3.0, 9.0, 0.4, 1.0), 1e-12);
}

TEST(DiskLight, Listing9VirtualPositionIsTheConeApex) {
    // The spot cone of half-angle θ from the virtual position passes through the disk's rim, so the
    // cone attenuation of lst:4 starts exactly at the disk's edge.
    const glm::dvec3 lightPos(1.0, 2.0, 3.0), dir = glm::normalize(glm::dvec3(0.2, -1.0, 0.1));
    const double radius = 0.3, halfOuter = deg(35);
    const glm::dvec3 apex = lighting::diskVirtualPosition(lightPos, dir, radius, halfOuter);
    const glm::dvec3 side = glm::normalize(glm::cross(dir, glm::dvec3(1, 0, 0)));
    const glm::dvec3 rim = lightPos + side * radius;
    EXPECT_NEAR(std::acos(glm::dot(glm::normalize(rim - apex), dir)), halfOuter, 1e-12);
    EXPECT_LT(glm::dot(apex - lightPos, dir), 0.0);  // behind the disk
}

TEST(Sun, Listing6DiskAndIlluminance) {
    const double sigma = deg(0.545 / 2);  // the sun's angular radius
    const glm::dvec3 D = glm::normalize(glm::dvec3(0.3, 0.2, 1.0));
    // eq:28: E⊥ ⟨n·D⟩.
    EXPECT_DOUBLE_EQ(lighting::sunIlluminance(100000.0, 0.5), 50000.0);
    EXPECT_DOUBLE_EQ(lighting::sunIlluminance(100000.0, -0.2), 0.0);
    // A reflection vector inside the disk is kept.
    const glm::dvec3 inside = glm::normalize(
        D + 0.5 * std::tan(sigma) * glm::normalize(glm::cross(D, glm::dvec3(0, 0, 1))));
    EXPECT_EQ(lighting::sunSpecularDirection(D, inside, sigma), inside);
    // Outside: the closest point of the rim, in the plane of D and R.
    const glm::dvec3 R = glm::normalize(glm::dvec3(0.0, 0.0, 1.0));
    const glm::dvec3 S = lighting::sunSpecularDirection(D, R, sigma);
    EXPECT_NEAR(glm::length(S), 1.0, 1e-12);
    EXPECT_NEAR(std::acos(glm::dot(S, D)), sigma, 1e-9);
    EXPECT_NEAR(glm::dot(S, glm::cross(D, R)), 0.0, 1e-12);
    EXPECT_GT(glm::dot(S, R), glm::dot(D, R));
    // The sun as a disk: 100 000 lx from 7.1e-5 sr is about 1.4e9 cd/m²; lit back through lst:10.
    const double L = lighting::sunLuminance(100000.0, sigma);
    EXPECT_NEAR(lighting::sunSolidAngle(sigma), 7.106e-5, 0.001e-5);
    EXPECT_NEAR(L, 1.41e9, 0.01e9);
    EXPECT_NEAR(L * lighting::illuminanceSphereOrDisk(1.0, std::sin(sigma) * std::sin(sigma)),
                100000.0, 1e-6);
}

// =============================================================================================
// Rectangle and tube lights (seed 002 §4.7.2.5, §4.7.2.6)
// =============================================================================================

TEST(RectangleLight, SolidAngleAndStructuredSamplingAgainstTheIntegral) {
    const glm::dvec3 center(0, 0, 2), left(1, 0, 0), up(0, 1, 0), emitNormal(0, 0, -1);
    const double w = 1.2, h = 0.8;
    const auto samples = [&](auto&& emit) {
        const int n = 600;
        for (int i = 0; i < n; ++i)
            for (int j = 0; j < n; ++j)
                emit(SurfaceSample{
                    center + left * (w * ((i + 0.5) / n - 0.5)) + up * (h * ((j + 0.5) / n - 0.5)),
                    emitNormal, w * h / (static_cast<double>(n) * n)});
    };
    // Solid angle: on axis the quad formula equals the right pyramid's.
    const glm::dvec3 x(0, 0, 0);
    const glm::dvec3 p0 = center - left * (w / 2) + up * (h / 2),
                     p1 = center - left * (w / 2) - up * (h / 2),
                     p2 = center + left * (w / 2) - up * (h / 2),
                     p3 = center + left * (w / 2) + up * (h / 2);
    EXPECT_NEAR(lighting::rectangleSolidAngle(x, p0, p1, p2, p3),
                lighting::rightPyramidSolidAngle(2.0, w / 2, h / 2), 1e-12);

    // Measured: 2.8 % low with the normal facing the light and tilted by 27° or 73°; +22 % for a
    // normal tilted 86° whose horizon cuts through the light (the five samples see too much of it).
    struct Case {
        glm::dvec3 n;
        double tolerance;
    };
    for (const Case c :
         {Case{glm::dvec3(0, 0, 1), 0.03}, Case{glm::normalize(glm::dvec3(0.5, 0, 1)), 0.03},
          Case{glm::normalize(glm::dvec3(1, 0, 0.3)), 0.03},
          Case{glm::normalize(glm::dvec3(1, 1, 0.1)), 0.25}}) {
        const double reference = surfaceIlluminanceReference(x, c.n, samples);
        const double approx =
            lighting::rectangleIlluminance(x, c.n, center, left, up, emitNormal, w, h);
        std::printf(
            "rectangle light, n = (%.2f %.2f %.2f): integral %.5f, structured sampling %.5f (%+.1f "
            "%%)\n",
            c.n.x, c.n.y, c.n.z, reference, approx, 100.0 * (approx - reference) / reference);
        EXPECT_NEAR(approx, reference, c.tolerance * reference);
    }
    // Behind the emitting side: nothing.
    EXPECT_EQ(lighting::rectangleIlluminance(glm::dvec3(0, 0, 3), glm::dvec3(0, 0, -1), center,
                                             left, up, emitNormal, w, h),
              0.0);
}

TEST(TubeLight, CapsuleApproximationAgainstTheIntegral) {
    // A capsule from p0 to p1: cylinder plus two half-spheres, integrated over its surface.
    const glm::dvec3 p0(-0.5, 0.0, 1.5), p1(0.5, 0.0, 1.5);
    const double radius = 0.05;
    const glm::dvec3 axis = glm::normalize(p1 - p0), e1(0, 1, 0), e2 = glm::cross(axis, e1);
    const double length = glm::length(p1 - p0);
    const auto samples = [&](auto&& emit) {
        const int n = 500;
        for (int i = 0; i < n; ++i) {  // cylinder
            const double t = length * (i + 0.5) / n;
            for (int j = 0; j < n; ++j) {
                const double psi = 2 * kPi * (j + 0.5) / n;
                const glm::dvec3 nrm = std::cos(psi) * e1 + std::sin(psi) * e2;
                emit(SurfaceSample{p0 + axis * t + radius * nrm, nrm,
                                   radius * (2 * kPi / n) * (length / n)});
            }
        }
        for (int end = 0; end < 2; ++end) {  // half-spheres, equal-area cells
            const glm::dvec3 c = end == 0 ? p0 : p1, out = end == 0 ? -axis : axis;
            for (int i = 0; i < n; ++i) {
                const double cz = (i + 0.5) / n, sz = std::sqrt(1 - cz * cz);
                for (int j = 0; j < n; ++j) {
                    const double psi = 2 * kPi * (j + 0.5) / n;
                    const glm::dvec3 nrm =
                        cz * out + sz * (std::cos(psi) * e1 + std::sin(psi) * e2);
                    emit(SurfaceSample{c + radius * nrm, nrm,
                                       radius * radius * 2 * kPi / (static_cast<double>(n) * n)});
                }
            }
        }
    };
    double worst = 0.0;
    for (const glm::dvec3 x :
         {glm::dvec3(0, 0, 0), glm::dvec3(0.8, 0, 0.3), glm::dvec3(0.2, 0.4, 0.2)}) {
        for (const glm::dvec3 n : {glm::dvec3(0, 0, 1), glm::normalize(glm::dvec3(0.4, 0.2, 1))}) {
            const double reference = surfaceIlluminanceReference(x, n, samples);
            const double approx = lighting::tubeIlluminance(x, n, p0, p1, radius);
            worst = std::max(worst, std::abs(approx - reference) / reference);
        }
    }
    std::printf("tube light, rectangle + sphere vs integral: worst relative error %.3f\n", worst);
    EXPECT_LT(worst, 0.10);
    // Far away (seed 002 §4.7.3, the five times rule) the tube is a point of intensity L × its
    // projected area, 2rl + πr² seen from the side: the inverse square law.
    const double far = 20.0, L = lighting::tubeLuminanceFromLumens(1000.0, radius, length);
    const double E =
        L * lighting::tubeIlluminance(glm::dvec3(0, far, 0), glm::dvec3(0, -1, 0),
                                      glm::dvec3(-0.5, 0, 0), glm::dvec3(0.5, 0, 0), radius);
    EXPECT_NEAR(E, L * (2 * radius * length + kPi * radius * radius) / (far * far), 0.01 * E);
}

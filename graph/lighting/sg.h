// Spherical Gaussians (seed 003, "Basic Mathematical Properties" and "Lighting with SGs"; the
// baked-GI lightmaps of Ready At Dawn): G(x) = A e^{λ (μ·x − 1)} with μ the unit mean (axis), λ the
// sharpness (the seed's 1 / W, its "width") and A the amplitude (RGB). The algebra the seed relies
// on, in closed form: evaluation, the integral over the sphere, the product of two SGs (another
// SG) and their inner product; and the irradiance an SG of radiance gives a surface, via the
// clamped cosine lobe as one SG (λ 2.133, A 1.17: Wang et al. 2009's fit, the usual choice).
#pragma once

#include <vector>

#include <glm/vec3.hpp>

namespace rg::lighting {

struct SphericalGaussian {
    glm::vec3 axis{0.0f, 0.0f, 1.0f};  // μ, unit
    float sharpness = 1.0f;            // λ > 0
    glm::vec3 amplitude{1.0f};         // A
};

// G(x) for unit x.
glm::vec3 evaluate(const SphericalGaussian& g, const glm::vec3& x);
// ∫ G dω over the sphere: 2π A / λ · (1 − e^{−2λ}).
glm::vec3 integral(const SphericalGaussian& g);
// G1 · G2 as one SG: axis ∝ λ1 μ1 + λ2 μ2, sharpness |λ1 μ1 + λ2 μ2|, amplitude A1 A2 e^{λm − λ1 − λ2}.
SphericalGaussian product(const SphericalGaussian& a, const SphericalGaussian& b);
// ∫ G1 G2 dω (the integral of the product).
glm::vec3 innerProduct(const SphericalGaussian& a, const SphericalGaussian& b);
// The clamped cosine lobe max(0, n·x) around n, approximated as an SG.
SphericalGaussian cosineLobe(const glm::vec3& n);
// Irradiance ∫ L(x) max(0, n·x) dω of the radiance SG `radiance` on a surface of normal n: the
// inner product with cosineLobe(n).
glm::vec3 irradiance(const SphericalGaussian& radiance, const glm::vec3& n);

// The seed's fixed lightmap basis ("Fixed Directions", "Fixed Widths"): n lobe axes spread evenly
// over the sphere by the golden-ratio spiral (z from 1 − 1/n down to −1 + 1/n in equal steps, the
// azimuth turning by the golden angle π (3 − √5) each step; `hemisphere` keeps z > 0 for a
// tangent-space basis), and one sharpness for them all, chosen so that neither gaps nor blur
// dominate: a lobe falls to one half at half the mean angle between neighbouring axes,
// λ = ln 2 / (1 − cos(θ̄ / 2)) — the lobes then overlap just enough for their sum to stay nearly
// flat (tests/unit/test_sg.cpp measures it for n = 5, 6, 9, 12).
std::vector<glm::vec3> goldenSpiralAxes(int n, bool hemisphere = false);
float basisSharpness(const std::vector<glm::vec3>& axes);

// The seed's coefficients are non-negative ("positive values only, which helps compression and
// precision"): the least-squares fit of radiance samples by the fixed basis under amplitudes ≥ 0,
// solved per colour channel by Lawson and Hanson's active-set NNLS (Solving Least Squares
// Problems, 1974, ch. 23) on the samples' design matrix. `directions` should cover the sphere
// (or the hemisphere) evenly: each sample weighs the same.
std::vector<glm::vec3> fitNonNegative(const std::vector<glm::vec3>& axes, float sharpness,
                                      const std::vector<glm::vec3>& directions,
                                      const std::vector<glm::vec3>& radiance);
// The same fit from its normal equations: `gram` the n × n matrix ∫ G_i G_j dω (row-major, e.g.
// basisGram) and `projections` the inner products ∫ G_k L dω of the radiance with each unit lobe
// (RGB) — what a baker estimates by Monte Carlo, delta lights included exactly (a delta of
// irradiance E from direction d projects to E · G_k(d)). The L2 projection under amplitudes ≥ 0.
std::vector<glm::vec3> fitNonNegative(const std::vector<double>& gram,
                                      const std::vector<glm::dvec3>& projections);
// ∫ G_i G_j dω of unit lobes over the sphere, or over the upper hemisphere (z > 0), by quadrature.
std::vector<double> basisGram(const std::vector<glm::vec3>& axes, float sharpness, bool hemisphere);
// Σ_k amplitude_k e^{λ (axis_k · x − 1)}: the fitted radiance in direction x.
glm::vec3 evaluateBasis(const std::vector<glm::vec3>& axes, float sharpness,
                        const std::vector<glm::vec3>& amplitudes, const glm::vec3& x);
// n directions spread evenly over the sphere (the golden spiral with n points): sample sets.
inline std::vector<glm::vec3> sphereSamples(int n) { return goldenSpiralAxes(n); }

}  // namespace rg::lighting

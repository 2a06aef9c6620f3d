#include "ltc.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include "area_lights.h"
#include "brdf.h"
#include "core/check.h"

namespace rg::ltc {

namespace {

constexpr double kPiD = 3.14159265358979323846;

// The fitted numbers as printed (decimal, double); converted to Entry once.
constexpr double kFitted[kSize * kSize][6] = {
#include "ltc_ggx.inc"
};

const std::array<Entry, size_t(kSize) * kSize>& fittedTable() {
    static const std::array<Entry, size_t(kSize)* kSize> t = [] {
        std::array<Entry, size_t(kSize) * kSize> out{};
        for (size_t i = 0; i < out.size(); ++i) {
            const double* f = kFitted[i];
            out[i].inverse = {float(f[0]), float(f[1]), float(f[2]), float(f[3])};
            out[i].magnitude = float(f[4]), out[i].fresnel = float(f[5]);
        }
        return out;
    }();
    return t;
}

// The view of a cell: in the plane xz, θv from the normal z.
glm::dvec3 viewVector(double NdotV) {
    return {std::sqrt(std::max(0.0, 1.0 - NdotV * NdotV)), 0.0, NdotV};
}

// The GGX lobe of brdf.glsl times ⟨n·l⟩ for one cell, D/π · Vis · ⟨n·l⟩ (F = 1), sampled by
// its visible normals.
// The standard GGX lobe with F = 1 times ⟨n·l⟩ (lst:2): D / π · Vis · ⟨n·l⟩.
double lobeValue(float NdotH, double NdotL, float NdotV, float alpha) {
    return double(brdf::D_GGX(NdotH, alpha)) / kPiD *
           double(brdf::V_SmithGGXCorrelated(float(NdotL), NdotV, alpha)) * NdotL;
}

struct LobeModel {
    float alpha;
    glm::dvec3 v;
    brdf::VisibleNormals vn;
    LobeModel(float linearRoughness, double NdotV)
        : alpha(brdf::standardAlpha(linearRoughness)), v(viewVector(NdotV)), vn(v, alpha) {}
    double value(const glm::dvec3& l) const {
        if (l.z <= 0.0) return 0.0;
        const glm::dvec3 h = glm::normalize(v + l);
        return lobeValue(static_cast<float>(std::max(h.z, 0.0)), l.z, static_cast<float>(v.z),
                         alpha);
    }
    glm::dvec3 sample(double u1, double u2) const {  // the light reflected about a visible normal
        const glm::dvec3 h = vn.halfVector(u1, u2);
        return 2.0 * glm::dot(v, h) * h - v;
    }
    double pdf(const glm::dvec3& l) const { return vn.pdf(l); }
};

glm::dmat3 matrixFromParameters(const glm::dvec3& direction, const glm::dvec3& p) {
    // M = [X Y Z] · [[m00, 0, m02], [0, m11, 0], [0, 0, 1]]; glm is column-major: m[col][row].
    const glm::dvec3 Z = direction, X(Z.z, 0.0, -Z.x), Y(0.0, 1.0, 0.0);
    glm::dmat3 s(1.0);
    s[0][0] = p.x;
    s[1][1] = p.y;
    s[2][0] = p.z;  // column 2, row 0
    return glm::dmat3(X, Y, Z) * s;
}

// Nelder–Mead in 4 dimensions.
template <class F>
glm::dvec4 nelderMead(F&& f, glm::dvec4 start, const glm::dvec4& step, int maxEvaluations,
                      double tolerance, int& evaluations) {
    constexpr size_t kN = 4;
    std::array<glm::dvec4, kN + 1> x;
    x.fill(start);
    for (size_t i = 0; i < kN; ++i) x[i + 1][int(i)] += step[int(i)];
    std::array<double, kN + 1> fx{};
    for (size_t i = 0; i <= kN; ++i) fx[i] = f(x[i]);
    evaluations = int(kN + 1);
    while (evaluations < maxEvaluations) {
        std::array<size_t, kN + 1> order{0, 1, 2, 3, 4};
        std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return fx[a] < fx[b]; });
        const size_t best = order[0], worst = order[kN], second = order[kN - 1];
        if (std::abs(fx[worst] - fx[best]) <= tolerance * (std::abs(fx[best]) + 1e-12)) break;
        glm::dvec4 centroid(0.0);
        for (size_t i = 0; i < kN; ++i) centroid += x[order[i]] / double(kN);
        const glm::dvec4 reflected = centroid + (centroid - x[worst]);
        const double fr = f(reflected);
        ++evaluations;
        if (fr < fx[best]) {
            const glm::dvec4 expanded = centroid + 2.0 * (centroid - x[worst]);
            const double fe = f(expanded);
            ++evaluations;
            if (fe < fr)
                x[worst] = expanded, fx[worst] = fe;
            else
                x[worst] = reflected, fx[worst] = fr;
        } else if (fr < fx[second]) {
            x[worst] = reflected, fx[worst] = fr;
        } else {
            const glm::dvec4 contracted = fr < fx[worst] ? centroid + 0.5 * (reflected - centroid)
                                                         : centroid + 0.5 * (x[worst] - centroid);
            const double fc = f(contracted);
            ++evaluations;
            if (fc < std::min(fr, fx[worst])) {
                x[worst] = contracted, fx[worst] = fc;
            } else {  // shrink towards the best
                for (size_t i = 0; i <= kN; ++i)
                    if (i != best) x[i] = x[best] + 0.5 * (x[i] - x[best]), fx[i] = f(x[i]);
                evaluations += int(kN);
            }
        }
    }
    size_t best = 0;
    for (size_t i = 1; i <= kN; ++i)
        if (fx[i] < fx[best]) best = i;
    return x[best];
}

}  // namespace

std::span<const Entry> table() { return fittedTable(); }

glm::vec2 tableCoordinates(float linearRoughness, float NdotV) {
    const float x = std::clamp(linearRoughness, 0.0f, 1.0f);
    const float y = std::sqrt(std::clamp(1.0f - NdotV, 0.0f, 1.0f));
    return {x * float(kSize - 1), y * float(kSize - 1)};
}

Entry lookup(float linearRoughness, float NdotV) {
    const glm::vec2 t = tableCoordinates(linearRoughness, NdotV);
    const int x0 = std::min(int(t.x), kSize - 2), y0 = std::min(int(t.y), kSize - 2);
    const float wx = t.x - float(x0), wy = t.y - float(y0);
    auto at = [](int x, int y) { return fittedTable()[size_t(y * kSize + x)]; };
    auto mix = [](const Entry& p, const Entry& q, float w) {
        Entry e;
        for (size_t i = 0; i < 4; ++i)
            e.inverse[i] = p.inverse[i] + (q.inverse[i] - p.inverse[i]) * w;
        e.magnitude = p.magnitude + (q.magnitude - p.magnitude) * w,
        e.fresnel = p.fresnel + (q.fresnel - p.fresnel) * w;
        return e;
    };
    return mix(mix(at(x0, y0), at(x0 + 1, y0), wx), mix(at(x0, y0 + 1), at(x0 + 1, y0 + 1), wx),
               wy);
}

glm::mat3 inverseMatrix(const std::array<float, 4>& e) {
    glm::mat3 m(0.0f);
    m[0][0] = e[0], m[2][0] = e[1], m[1][1] = 1.0f, m[0][2] = e[2], m[2][2] = e[3];
    return m;
}

Moments lobeMoments(float linearRoughness, float NdotV, int samples) {
    const LobeModel lobe(linearRoughness, NdotV);
    Moments m;
    glm::dvec3 direction(0.0);
    for (int i = 0; i < samples; ++i)
        for (int j = 0; j < samples; ++j) {
            const glm::dvec3 l = lobe.sample((i + 0.5) / samples, (j + 0.5) / samples);
            const double pdf = lobe.pdf(l);
            if (l.z <= 0.0 || pdf <= 0.0) continue;
            const double w = lobe.value(l) / pdf;
            const double VdotH = glm::dot(lobe.v, glm::normalize(lobe.v + l));
            m.magnitude += w;
            m.fresnel += w * std::pow(std::max(0.0, 1.0 - VdotH), 5.0);
            direction += w * l;
        }
    const double n = double(samples) * samples;
    m.magnitude /= n;
    m.fresnel /= n;
    direction.y = 0.0;
    m.direction = glm::length(direction) > 0.0 ? glm::normalize(direction) : glm::dvec3(0, 0, 1);
    return m;
}

double distribution(const glm::dmat3& inverse, const glm::dvec3& w) {
    const glm::dvec3 lo = inverse * w;
    const double l = glm::length(lo);
    if (l <= 0.0) return 0.0;
    const double z = lo.z / l;
    return std::max(z, 0.0) / kPiD * std::abs(glm::determinant(inverse)) / (l * l * l);
}

namespace {

// ∫ |D − f/magnitude| dω by multiple importance sampling of the LTC and the lobe.
double difference(const LobeModel& lobe, const glm::dmat3& inverse, double magnitude, int samples) {
    const glm::dmat3 M = glm::inverse(inverse);
    double error = 0.0;
    auto term = [&](const glm::dvec3& l) {
        const double d = distribution(inverse, l);
        const double b = lobe.value(l) / magnitude;
        const double pdf = 0.5 * d + 0.5 * lobe.pdf(l);
        return pdf > 0.0 ? std::abs(d - b) / pdf : 0.0;
    };
    for (int i = 0; i < samples; ++i)
        for (int j = 0; j < samples; ++j) {
            const double u1 = (i + 0.5) / samples, u2 = (j + 0.5) / samples;
            // One sample of the LTC (a cosine-distributed direction through M), one of the lobe.
            const double r = std::sqrt(u1), phi = 2.0 * kPiD * u2;
            const glm::dvec3 lo(r * std::cos(phi), r * std::sin(phi),
                                std::sqrt(std::max(0.0, 1.0 - u1)));
            error += term(glm::normalize(M * lo));
            error += term(lobe.sample(u1, u2));
        }
    return error / (2.0 * double(samples) * samples);
}

}  // namespace

double fitDistance(float linearRoughness, float NdotV, const glm::mat3& inverse, int samples) {
    const LobeModel lobe(linearRoughness, NdotV);
    return difference(lobe, glm::dmat3(inverse), lobeMoments(linearRoughness, NdotV).magnitude,
                      samples);
}

Fit fitCell(float linearRoughness, float NdotV, const glm::dvec4* start, glm::dvec4* parameters,
            int samples) {
    const LobeModel lobe(linearRoughness, NdotV);
    const Moments m = lobeMoments(linearRoughness, NdotV);
    const double alpha = brdf::standardAlpha(linearRoughness);
    const glm::dvec4 first = start ? *start : glm::dvec4(alpha, alpha, 0.0, 0.0);
    const double base = std::atan2(m.direction.x, m.direction.z);
    auto matrix = [&](const glm::dvec4& p) {
        const double angle = base + p.w;
        return matrixFromParameters(glm::dvec3(std::sin(angle), 0.0, std::cos(angle)),
                                    glm::dvec3(p));
    };
    // The L1 distance: it weighs the lobe's tails, where a light beside the highlight falls, more
    // than Heitz et al.'s cubed one, which favours the peak.
    auto objective = [&](const glm::dvec4& p) {
        if (p.x <= 1e-6 || p.y <= 1e-6 || std::abs(p.w) > 1.0) return 1e30;
        return difference(lobe, glm::inverse(matrix(p)), m.magnitude, samples);
    };
    Fit fit;
    const glm::dvec4 step(0.05 * std::max(1e-3, first.x), 0.05 * std::max(1e-3, first.y),
                          0.05 * std::max(1e-3, std::abs(first.z)) + 1e-3, 0.02);
    const glm::dvec4 p = nelderMead(objective, first, step, 1000, 1e-6, fit.evaluations);
    if (parameters) *parameters = p;
    fit.error = objective(p);
    const glm::dmat3 inverse = glm::inverse(matrix(p));
    const double k = 1.0 / inverse[1][1];
    fit.entry.inverse = {float(inverse[0][0] * k), float(inverse[2][0] * k),
                         float(inverse[0][2] * k), float(inverse[2][2] * k)};
    fit.entry.magnitude = float(m.magnitude);
    fit.entry.fresnel = float(m.fresnel);
    return fit;
}

// ---- Integrals ---------------------------------------------------------------------------------

namespace {

// The form factor's edge term: acos(v1·v2) · normalize(v1 × v2) for unit v1, v2 (the angle by
// atan2, which keeps its precision for short edges).
glm::vec3 edgeVector(const glm::vec3& v1, const glm::vec3& v2) {
    const glm::vec3 c = glm::cross(v1, v2);
    const float s = glm::length(c);
    const float angle = std::atan2(s, glm::dot(v1, v2));
    return s > 1e-12f ? c * (angle / s) : glm::vec3(0.0f);
}

}  // namespace

namespace {

// Sutherland–Hodgman against the plane z = 0; what it keeps, taken through `m`.
std::vector<glm::vec3> keepAbove(std::span<const glm::vec3> vertices,
                                 const glm::mat3& m = glm::mat3(1.0f)) {
    std::vector<glm::vec3> kept;
    const size_t n = vertices.size();
    for (size_t i = 0; i < n; ++i) {
        const glm::vec3 a = vertices[i], b = vertices[(i + 1) % n];
        if (a.z > 0.0f) kept.push_back(m * a);
        if ((a.z > 0.0f) != (b.z > 0.0f)) kept.push_back(m * (a + (b - a) * (a.z / (a.z - b.z))));
    }
    return kept;
}

}  // namespace

float polygonIntegral(std::span<const glm::vec3> vertices, glm::vec3* direction) {
    const std::vector<glm::vec3> clipped = keepAbove(vertices);
    glm::vec3 sum(0.0f);
    for (size_t i = 0; i < clipped.size(); ++i)
        sum += edgeVector(glm::normalize(clipped[i]),
                          glm::normalize(clipped[(i + 1) % clipped.size()]));
    if (direction) *direction = sum.z < 0.0f ? -sum : sum;
    return std::abs(sum.z) / (2.0f * float(kPiD));
}

float ellipseIntegral(glm::vec3 centre, glm::vec3 axis1, glm::vec3 axis2, glm::vec3* direction) {
    // The ellipse's principal axes: the eigenvectors u of the Gram matrix of (axis1, axis2) give
    // them as [axis1 axis2] · u, of lengths √eigenvalue.
    const float d11 = glm::dot(axis1, axis1), d22 = glm::dot(axis2, axis2),
                d12 = glm::dot(axis1, axis2);
    glm::vec3 t1 = axis1, t2 = axis2;
    float e1 = d11, e2 = d22;
    if (std::abs(d12) > 1e-4f * std::sqrt(d11 * d22)) {
        const float mean = 0.5f * (d11 + d22),
                    spread = std::sqrt(0.25f * (d11 - d22) * (d11 - d22) + d12 * d12);
        e1 = mean + spread, e2 = std::max(mean - spread, 0.0f);
        t1 = d11 > d22 ? axis1 * d12 + axis2 * (e1 - d11) : axis1 * (e1 - d22) + axis2 * d12;
        t2 = glm::cross(glm::cross(axis1, axis2), t1);
    }
    t1 = glm::normalize(t1), t2 = glm::normalize(t2);
    glm::vec3 t3 = glm::cross(t1, t2);
    float h = glm::dot(t3, centre);
    if (h < 0.0f) t3 = -t3, h = -h;
    if (h < 1e-7f * std::sqrt(e1)) {  // seen edge on
        if (direction) *direction = glm::vec3(0, 0, 1);
        return 0.0f;
    }
    // Scaled so that the ellipse's plane is z = 1 in the frame (t1, t2, t3): centre (x0, y0, 1),
    // half-axes a1, a2. Its cone: ((x − x0 z)/a1)² + ((y − y0 z)/a2)² − z² = 0, the quadric Q; the
    // eigenvalues of Q are λ1, λ2 > 0 and λ3 ∈ [−1, −1/(1 + x0² + y0²)] (Weyl; the Rayleigh
    // quotient at (x0, y0, 1)). λ3 is the root there of det(Q − λ) / (pq), p = 1/a1², q = 1/a2²:
    //   g(λ) = a1²a2² λ³ − ((1 + x0²) a2² + (1 + y0²) a1² − a1²a2²) λ² + (1 + x0² + y0² − a1² − a2²) λ + 1,
    // well scaled for small and large ellipses alike; the other two enter only through their sum
    // and product, so the cone's tan² half-angles L1² = −λ3/λ1, L2² = −λ3/λ2 follow from λ3 alone.
    const float x0 = glm::dot(t1, centre) / h, y0 = glm::dot(t2, centre) / h;
    const float a1s = e1 / (h * h), a2s = e2 / (h * h);
    const float k3 = a1s * a2s, k2 = (1.0f + x0 * x0) * a2s + (1.0f + y0 * y0) * a1s - a1s * a2s;
    const float k1 = 1.0f + x0 * x0 + y0 * y0 - a1s - a2s;
    float lo = -1.0f, hi = -1.0f / (1.0f + x0 * x0 + y0 * y0), lambda = hi;
    for (int i = 0; i < 12;
         ++i) {  // Newton, kept inside the bracket (bisection where it leaves it)
        const float g = ((k3 * lambda - k2) * lambda + k1) * lambda + 1.0f;
        if (g > 0.0f)
            hi = lambda;
        else
            lo = lambda;
        const float dg = (3.0f * k3 * lambda - 2.0f * k2) * lambda + k1;
        float next = dg != 0.0f ? lambda - g / dg : 0.5f * (lo + hi);
        if (!(next > lo && next < hi)) next = 0.5f * (lo + hi);
        lambda = next;
    }
    // λ1 λ2 = −pq/λ3 and λ1 + λ2 = tr Q − λ3, with tr Q / (pq) = k2 and 1/(pq) = k3:
    const float productTan = -lambda * lambda * lambda * k3;  // L1² L2² = λ3² / (λ1 λ2)
    const float sumTan =
        lambda * lambda * (k2 - lambda * k3);  // L1² + L2² = −λ3 (λ1 + λ2) / (λ1 λ2)
    const float formFactor = std::sqrt(std::max(productTan, 0.0f) / (1.0f + sumTan + productTan));
    const glm::vec3 axis =
        glm::normalize(t1 * (x0 / (1.0f - lambda * a1s)) + t2 * (y0 / (1.0f - lambda * a2s)) + t3);
    if (direction) *direction = axis;
    return float(lighting::illuminanceSphereOrDisk(std::clamp(double(axis.z), -0.9999, 0.9999),
                                                   std::min(double(formFactor), 0.9999)) /
                 kPiD);
}

float horizonPolygonIntegral(std::span<const glm::vec3> local, const glm::mat3& tableInverse,
                             glm::vec3* direction) {
    const std::vector<glm::vec3> above = keepAbove(local, tableInverse);
    if (above.empty()) {
        if (direction) *direction = glm::vec3(0.0f);
        return 0.0f;
    }
    return polygonIntegral(above, direction);
}

float lobeRatio(const glm::mat3& inverse, glm::vec3 N, glm::vec3 V, float alpha, float magnitude,
                glm::vec3 mean) {
    const float det = std::abs(glm::determinant(inverse));
    if (magnitude <= 0.0f || det <= 0.0f || glm::dot(mean, mean) <= 0.0f) return 1.0f;
    const glm::vec3 L = glm::normalize(glm::inverse(inverse) * mean);
    const float D = float(distribution(glm::dmat3(inverse), glm::dvec3(L)));
    const float NdotL = glm::dot(N, L);
    if (D <= 0.0f || NdotL <= 0.0f) return 1.0f;  // (the fade below is 0 there)
    const float NdotV = std::abs(glm::dot(N, V)) + 1e-5f;
    const float NdotH = std::clamp(glm::dot(N, glm::normalize(V + L)), 0.0f, 1.0f);
    const float lobe = float(lobeValue(NdotH, NdotL, NdotV, alpha));
    // Faded out towards either horizon, where the ratio changes too fast across a light for one
    // direction to stand for it, or D → 0 (smoothstep over ⟨n·l⟩ and the cosine-space elevation 0..0.25).
    const glm::vec3 o = inverse * L;
    const auto step = [](float x) {
        const float t = std::clamp(x / 0.25f, 0.0f, 1.0f);
        return t * t * (3.0f - 2.0f * t);
    };
    const float fade = step(NdotL) * step(o.z / glm::length(o));
    return 1.0f + (lobe / (magnitude * D) - 1.0f) * fade;
}

float sphereRatio(const glm::mat3& inverse, glm::vec3 N, glm::vec3 V, float alpha, float magnitude,
                  glm::vec3 L, float sinSigmaSqr) {
    const float det = std::abs(glm::determinant(inverse));
    if (magnitude <= 0.0f || det <= 0.0f) return 1.0f;
    const float oneMinusCos = 1.0f - std::sqrt(1.0f - sinSigmaSqr);
    const glm::vec3 t1 = glm::normalize(
        glm::cross(L, std::abs(L.y) < 0.99f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0)));
    const glm::vec3 t2 = glm::cross(L, t1);
    const float NdotV = std::abs(glm::dot(N, V)) + 1e-5f;
    double lobe = 0.0, fitted = 0.0;
    for (int k = 0; k < kSphereRatioTaps; ++k) {
        const float cosTheta = 1.0f - oneMinusCos * (float(k) + 0.5f) / float(kSphereRatioTaps);
        const float sinTheta = std::sqrt(std::max(1.0f - cosTheta * cosTheta, 0.0f));
        const float phi = float(k) * 2.39996323f;
        const glm::vec3 l = L * cosTheta + (t1 * std::cos(phi) + t2 * std::sin(phi)) * sinTheta;
        const float NdotL = glm::dot(N, l);
        if (NdotL <= 0.0f) continue;  // both are 0 below the shading horizon
        const float NdotH = std::clamp(glm::dot(N, glm::normalize(V + l)), 0.0f, 1.0f);
        lobe += lobeValue(NdotH, NdotL, NdotV, alpha);
        fitted += distribution(glm::dmat3(inverse), glm::dvec3(l));
    }
    return fitted > 0.0 ? float(lobe / (double(magnitude) * fitted)) : 1.0f;
}

}  // namespace rg::ltc

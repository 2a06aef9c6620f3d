// LDR-FLIP: "FLIP: A Difference Evaluator for Alternating Images", Andersson, Nilsson,
// Akenine-Möller, Oskarsson, Åström, Fairchild, HPG 2020. Written from the paper's equations;
// the constants are the paper's. Two pipelines meet at the end:
//  - colour: sRGB -> linear -> XYZ -> YCxCz (linearised CIELAB), each channel filtered with its
//    contrast sensitivity function (sums of Gaussians, eq. 2-3), back to linear RGB clamped to
//    the unit cube, then CIELAB with the Hunt adjustment and the HyAB distance (eq. 4-5),
//    compressed with exponent 0.7 and redistributed to [0, 1] against the distance from green
//    to blue (eq. 6);
//  - features: edges (first derivative of a Gaussian) and points (second derivative) of the
//    luminance, their magnitudes compared (eq. 7-8).
// FLIP = colour^(1 - feature) per pixel. Borders replicate the edge pixels.
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "golden/metrics.h"

namespace rg::golden {

namespace {

constexpr double kPi = 3.14159265358979323846;

using Vec3 = std::array<double, 3>;

// One channel of doubles, row-major.
struct Plane {
    uint32_t w = 0, h = 0;
    std::vector<double> v;
    Plane(uint32_t width, uint32_t height) : w(width), h(height), v(size_t(width) * height, 0.0) {}
    double& at(uint32_t x, uint32_t y) { return v[size_t(y) * w + x]; }
    double at(uint32_t x, uint32_t y) const { return v[size_t(y) * w + x]; }
};

// Separable correlation with a centred kernel of odd length; edges replicate.
Plane filterRows(const Plane& in, const std::vector<double>& k) {
    Plane out(in.w, in.h);
    const int r = static_cast<int>(k.size() / 2);
    const int w = static_cast<int>(in.w);
    for (uint32_t y = 0; y < in.h; ++y)
        for (int x = 0; x < w; ++x) {
            double s = 0.0;
            for (int i = -r; i <= r; ++i)
                s += k[static_cast<size_t>(i + r)] *
                     in.at(static_cast<uint32_t>(std::clamp(x + i, 0, w - 1)), y);
            out.at(static_cast<uint32_t>(x), y) = s;
        }
    return out;
}

Plane filterCols(const Plane& in, const std::vector<double>& k) {
    Plane out(in.w, in.h);
    const int r = static_cast<int>(k.size() / 2);
    const int h = static_cast<int>(in.h);
    for (int y = 0; y < h; ++y)
        for (uint32_t x = 0; x < in.w; ++x) {
            double s = 0.0;
            for (int i = -r; i <= r; ++i)
                s += k[static_cast<size_t>(i + r)] *
                     in.at(x, static_cast<uint32_t>(std::clamp(y + i, 0, h - 1)));
            out.at(x, static_cast<uint32_t>(y)) = s;
        }
    return out;
}

// sRGB primaries, D65 white (IEC 61966-2-1), as exact ratios.
constexpr double kRgbToXyz[3][3] = {
    {10135552.0 / 24577794.0, 8788810.0 / 24577794.0, 4435075.0 / 24577794.0},
    {2613072.0 / 12288897.0, 8788810.0 / 12288897.0, 887015.0 / 12288897.0},
    {1425312.0 / 73733382.0, 8788810.0 / 73733382.0, 70074185.0 / 73733382.0},
};
constexpr Vec3 kWhite = {0.950428545, 1.0, 1.088900371};  // D65 XYZ of linear RGB (1, 1, 1)

Vec3 mul(const double m[3][3], const Vec3& v) {
    return {m[0][0] * v[0] + m[0][1] * v[1] + m[0][2] * v[2],
            m[1][0] * v[0] + m[1][1] * v[1] + m[1][2] * v[2],
            m[2][0] * v[0] + m[2][1] * v[1] + m[2][2] * v[2]};
}

struct Matrices {
    double xyzToRgb[3][3];
    Matrices() {
        const auto& m = kRgbToXyz;
        const double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                           m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                           m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c) {
                // Inverse = adjugate / det; the adjugate's (r, c) is the cofactor of (c, r).
                const int r1 = (c + 1) % 3, r2 = (c + 2) % 3, c1 = (r + 1) % 3, c2 = (r + 2) % 3;
                xyzToRgb[r][c] = (m[r1][c1] * m[r2][c2] - m[r1][c2] * m[r2][c1]) / det;
            }
    }
};
const Matrices& matrices() {
    static const Matrices m;
    return m;
}

// Linear RGB -> YCxCz (the linearised CIELAB of FLIP, eq. 1).
Vec3 rgbToYcxcz(const Vec3& rgb) {
    Vec3 xyz = mul(kRgbToXyz, rgb);
    const double x = xyz[0] / kWhite[0], y = xyz[1] / kWhite[1], z = xyz[2] / kWhite[2];
    return {116.0 * y - 16.0, 500.0 * (x - y), 200.0 * (y - z)};
}

Vec3 ycxczToRgb(const Vec3& c) {
    const double y = (c[0] + 16.0) / 116.0;
    const Vec3 xyz = {(y + c[1] / 500.0) * kWhite[0], y * kWhite[1],
                      (y - c[2] / 200.0) * kWhite[2]};
    return mul(matrices().xyzToRgb, xyz);
}

// Linear RGB -> CIELAB with the Hunt adjustment (a and b scaled by 0.01 L).
Vec3 rgbToHuntLab(const Vec3& rgb) {
    const Vec3 xyz = mul(kRgbToXyz, rgb);
    constexpr double d = 6.0 / 29.0;
    auto f = [&](double t) {
        return t > d * d * d ? std::cbrt(t) : t / (3.0 * d * d) + 4.0 / 29.0;
    };
    const double fx = f(xyz[0] / kWhite[0]), fy = f(xyz[1] / kWhite[1]), fz = f(xyz[2] / kWhite[2]);
    const double L = 116.0 * fy - 16.0;
    return {L, 0.01 * L * 500.0 * (fx - fy), 0.01 * L * 200.0 * (fy - fz)};
}

double hyab(const Vec3& a, const Vec3& b) {
    return std::fabs(a[0] - b[0]) +
           std::sqrt((a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

// Contrast sensitivity of one opponent channel as a sum of two Gaussians in visual degrees
// (eq. 2): a1 sqrt(pi / b1) exp(-pi^2 r^2 / b1) + a2 ... Both terms are separable.
struct Csf {
    double a1, b1, a2, b2;
};
constexpr Csf kCsfA = {1.0, 0.0047, 0.0, 1e-5}, kCsfRg = {1.0, 0.0053, 0.0, 1e-5},
              kCsfBy = {34.1, 0.04, 13.5, 0.025};

Plane csfFilter(const Plane& in, const Csf& c, double ppd) {
    // The radius covers 3 standard deviations of the widest Gaussian of all three channels.
    const double widest = 0.04;
    const int r = static_cast<int>(std::ceil(3.0 * std::sqrt(widest / (2.0 * kPi * kPi)) * ppd));
    struct Term {
        double weight;
        std::vector<double> g;
        double sum;
    };
    std::vector<Term> terms;
    for (auto [a, b] : {std::pair{c.a1, c.b1}, std::pair{c.a2, c.b2}}) {
        if (a == 0.0) continue;
        Term t{a * std::sqrt(kPi / b), {}, 0.0};
        for (int i = -r; i <= r; ++i) {
            const double x = double(i) / ppd;
            t.g.push_back(std::exp(-kPi * kPi * x * x / b));
            t.sum += t.g.back();
        }
        terms.push_back(std::move(t));
    }
    // The 2D kernel is normalised to sum 1: its sum is the sum over terms of weight * sum(g)^2.
    double total = 0.0;
    for (const auto& t : terms) total += t.weight * t.sum * t.sum;
    Plane out(in.w, in.h);
    for (const auto& t : terms) {
        Plane p = filterCols(filterRows(in, t.g), t.g);
        const double s = t.weight / total;
        for (size_t i = 0; i < out.v.size(); ++i) out.v[i] += s * p.v[i];
    }
    return out;
}

// Edge (first derivative) and point (second derivative) detectors of eq. 7: Gaussian derivative
// kernels whose positive weights sum to 1 and negative weights to -1, times a Gaussian across.
struct FeatureKernels {
    std::vector<double> edge, point, blur;
};

FeatureKernels featureKernels(double ppd) {
    const double sd = 0.5 * 0.082 * ppd;  // 0.082 degrees: peak-to-trough width of edge detection
    const int r = static_cast<int>(std::ceil(3.0 * sd));
    FeatureKernels k;
    double blurSum = 0.0;
    for (int i = -r; i <= r; ++i) {
        const double x = double(i);
        const double g = std::exp(-x * x / (2.0 * sd * sd));
        k.blur.push_back(g);
        k.edge.push_back(-x * g);
        k.point.push_back((x * x / (sd * sd) - 1.0) * g);
        blurSum += g;
    }
    for (double& v : k.blur) v /= blurSum;
    for (auto* d : {&k.edge, &k.point}) {
        double pos = 0.0, neg = 0.0;
        for (double v : *d) (v > 0 ? pos : neg) += v;
        for (double& v : *d) v = v > 0 ? v / pos : (v < 0 ? v / -neg : 0.0);
    }
    return k;
}

// Per-pixel magnitude of the edge and point responses of a luminance plane.
std::pair<Plane, Plane> features(const Plane& y, const FeatureKernels& k) {
    Plane edgeX = filterCols(filterRows(y, k.edge), k.blur),
          edgeY = filterRows(filterCols(y, k.edge), k.blur);
    Plane pointX = filterCols(filterRows(y, k.point), k.blur),
          pointY = filterRows(filterCols(y, k.point), k.blur);
    for (size_t i = 0; i < edgeX.v.size(); ++i) {
        edgeX.v[i] = std::hypot(edgeX.v[i], edgeY.v[i]);
        pointX.v[i] = std::hypot(pointX.v[i], pointY.v[i]);
    }
    return {std::move(edgeX), std::move(pointX)};
}

struct Prepared {
    Plane c[3];  // YCxCz
    Plane lum;   // relative luminance Y / Yn, what the feature detectors see
    Prepared(uint32_t w, uint32_t h) : c{Plane(w, h), Plane(w, h), Plane(w, h)}, lum(w, h) {}
};

Prepared prepare(const Image& img, DisplayEncoding display) {
    Prepared p(img.width, img.height);
    for (uint32_t y = 0; y < img.height; ++y)
        for (uint32_t x = 0; x < img.width; ++x) {
            Vec3 rgb;
            for (uint32_t k = 0; k < 3; ++k) {
                float v = img.at(x, y, img.channels == 1 ? 0 : k);
                v = std::isnan(v) ? 0.0f : std::clamp(v, 0.0f, 1.0f);
                rgb[k] = display == DisplayEncoding::Srgb ? srgbDecode(v) : v;
            }
            const Vec3 c = rgbToYcxcz(rgb);
            for (int k = 0; k < 3; ++k) p.c[k].at(x, y) = c[static_cast<size_t>(k)];
            p.lum.at(x, y) = (c[0] + 16.0) / 116.0;
        }
    return p;
}

}  // namespace

Result<Image> flipErrorMap(const Image& reference, const Image& test, DisplayEncoding display,
                           double ppd) {
    if (reference.width != test.width || reference.height != test.height ||
        reference.channels != test.channels)
        return fail(ErrorCode::InvalidInput, "flip: the images differ in shape");
    if (reference.channels != 1 && reference.channels != 3)
        return fail(ErrorCode::InvalidInput,
                    "flip: compares 1 (grey) or 3 (colour) channels, got " +
                        std::to_string(reference.channels));
    if (!(ppd > 0.0) || ppd > 1000.0)
        return fail(ErrorCode::InvalidInput,
                    "flip: pixels per degree must be in (0, 1000], got " + formatNumber(ppd));
    const uint32_t w = reference.width, h = reference.height;
    Prepared ref = prepare(reference, display), tst = prepare(test, display);

    // Colour pipeline.
    const Csf* csf[3] = {&kCsfA, &kCsfRg, &kCsfBy};
    Plane fr[3] = {Plane(w, h), Plane(w, h), Plane(w, h)},
          ft[3] = {Plane(w, h), Plane(w, h), Plane(w, h)};
    for (int k = 0; k < 3; ++k) {
        fr[k] = csfFilter(ref.c[k], *csf[k], ppd);
        ft[k] = csfFilter(tst.c[k], *csf[k], ppd);
    }
    constexpr double qc = 0.7, qf = 0.5, pc = 0.4, pt = 0.95;
    const double cmax = std::pow(hyab(rgbToHuntLab({0, 1, 0}), rgbToHuntLab({0, 0, 1})), qc);
    auto labAt = [&](const Plane* f, size_t i) {
        Vec3 rgb = ycxczToRgb({f[0].v[i], f[1].v[i], f[2].v[i]});
        for (double& c : rgb) c = std::clamp(c, 0.0, 1.0);
        return rgbToHuntLab(rgb);
    };

    // Feature pipeline.
    const FeatureKernels fk = featureKernels(ppd);
    auto [edgeR, pointR] = features(ref.lum, fk);
    auto [edgeT, pointT] = features(tst.lum, fk);

    Image out(w, h, 1);
    for (size_t i = 0; i < size_t(w) * h; ++i) {
        const double de = std::pow(hyab(labAt(fr, i), labAt(ft, i)), qc);
        const double colour = de < pc * cmax
                                  ? pt / (pc * cmax) * de
                                  : pt + (de - pc * cmax) / (cmax - pc * cmax) * (1.0 - pt);
        const double feat = std::pow(
            std::max(std::fabs(edgeR.v[i] - edgeT.v[i]), std::fabs(pointR.v[i] - pointT.v[i])) /
                std::sqrt(2.0),
            qf);
        out.pixels[i] = static_cast<float>(std::pow(colour, 1.0 - feat));
    }
    return out;
}

}  // namespace rg::golden

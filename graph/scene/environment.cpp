#include "environment.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <glm/geometric.hpp>

namespace rg {

namespace {

constexpr float kPi = 3.14159265358979f;

// Perez et al.'s sky luminance distribution, F(θ, γ) = (1 + A e^(B / cos θ)) (1 + C e^(D γ) + E cos² γ)
// (Preetham 1999, eq. 3), θ from the zenith, γ from the sun.
struct Perez {
    float A, B, C, D, E;
    float operator()(float cosTheta, float gamma, float cosGamma) const {
        return (1.0f + A * std::exp(B / std::max(cosTheta, 0.01f))) *
               (1.0f + C * std::exp(D * gamma) + E * cosGamma * cosGamma);
    }
};

// Preetham 1999, appendix A.2: the distribution coefficients as linear functions of turbidity.
Perez perezY(float T) {
    return {0.1787f * T - 1.4630f, -0.3554f * T + 0.4275f, -0.0227f * T + 5.3251f,
            0.1206f * T - 2.5771f, -0.0670f * T + 0.3703f};
}
Perez perezX(float T) {
    return {-0.0193f * T - 0.2592f, -0.0665f * T + 0.0008f, -0.0004f * T + 0.2125f,
            -0.0641f * T - 0.8989f, -0.0033f * T + 0.0452f};
}
Perez perezYc(float T) {
    return {-0.0167f * T - 0.2608f, -0.0950f * T + 0.0092f, -0.0079f * T + 0.2102f,
            -0.0441f * T - 1.6537f, -0.0109f * T + 0.0529f};
}

// CIE XYZ (Y in cd/m²) → linear Rec.709 (sRGB primaries, D65).
glm::vec3 xyzToRec709(glm::vec3 c) {
    return {3.2404542f * c.x - 1.5371385f * c.y - 0.4985314f * c.z,
            -0.9692660f * c.x + 1.8760108f * c.y + 0.0415560f * c.z,
            0.0556434f * c.x - 0.2040259f * c.y + 1.0572252f * c.z};
}

}  // namespace

glm::vec3 sampleEquirect(const Image& img, glm::vec2 uv) {
    const float x = uv.x * static_cast<float>(img.width) - 0.5f;
    const float y = std::clamp(uv.y * static_cast<float>(img.height) - 0.5f, 0.0f,
                               static_cast<float>(img.height - 1));
    const float fx = std::floor(x), fy = std::floor(y);
    const float tx = x - fx, ty = y - fy;
    auto wrapX = [&](long i) {
        const long w = img.width;
        return static_cast<uint32_t>(((i % w) + w) % w);
    };
    const uint32_t x0 = wrapX(static_cast<long>(fx)), x1 = wrapX(static_cast<long>(fx) + 1);
    const uint32_t y0 = static_cast<uint32_t>(fy), y1 = std::min(y0 + 1, img.height - 1);
    glm::vec3 out(0.0f);
    for (uint32_t c = 0; c < 3; ++c) {
        const uint32_t ch = std::min(c, img.channels - 1);
        const float top = img.at(x0, y0, ch) * (1 - tx) + img.at(x1, y0, ch) * tx;
        const float bottom = img.at(x0, y1, ch) * (1 - tx) + img.at(x1, y1, ch) * tx;
        out[static_cast<int>(c)] = top * (1 - ty) + bottom * ty;
    }
    return out;
}

glm::vec2 equirectUv(glm::vec3 d) {
    return {0.5f + std::atan2(d.x, -d.z) / (2.0f * kPi),
            std::acos(std::clamp(d.y, -1.0f, 1.0f)) / kPi};
}

glm::vec3 equirectDirection(glm::vec2 uv) {
    const float phi = (uv.x - 0.5f) * 2.0f * kPi, theta = uv.y * kPi;
    return {std::sin(theta) * std::sin(phi), std::cos(theta), -std::sin(theta) * std::cos(phi)};
}

glm::vec3 preethamSky(glm::vec3 direction, const SkyParams& p) {
    const float T = p.turbidity;
    const glm::vec3 s = glm::normalize(p.toSun);
    const float thetaS = std::acos(std::clamp(s.y, 0.0f, 1.0f));  // a sun under the horizon: at it
    const float cosTheta = std::max(direction.y, 0.0f);
    const float cosGamma = std::clamp(glm::dot(direction, s), -1.0f, 1.0f);
    const float gamma = std::acos(cosGamma);
    // Zenith luminance in kcd/m² (Preetham eq. A.1 with χ) and chromaticity (A.2's polynomials).
    const float chi = (4.0f / 9.0f - T / 120.0f) * (kPi - 2.0f * thetaS);
    const float Yz =
        std::max(0.0f, (4.0453f * T - 4.9710f) * std::tan(chi) - 0.2155f * T + 2.4192f) * 1000.0f;
    const float t3 = thetaS * thetaS * thetaS, t2 = thetaS * thetaS;
    const float xz = T * T * (0.00166f * t3 - 0.00375f * t2 + 0.00209f * thetaS) +
                     T * (-0.02903f * t3 + 0.06377f * t2 - 0.03202f * thetaS + 0.00394f) +
                     (0.11693f * t3 - 0.21196f * t2 + 0.06052f * thetaS + 0.25886f);
    const float yz = T * T * (0.00275f * t3 - 0.00610f * t2 + 0.00317f * thetaS) +
                     T * (-0.04214f * t3 + 0.08970f * t2 - 0.04153f * thetaS + 0.00516f) +
                     (0.15346f * t3 - 0.26756f * t2 + 0.06670f * thetaS + 0.26688f);
    // Each quantity relative to its zenith value: F(θ, γ) / F(0, θs) (eq. 4).
    auto rel = [&](const Perez& f) {
        return f(cosTheta, gamma, cosGamma) / f(1.0f, thetaS, std::cos(thetaS));
    };
    const float Y = Yz * rel(perezY(T)) * (p.sunLux / kClearSkySunLux);
    const float x = xz * rel(perezX(T)), y = yz * rel(perezYc(T));
    if (y <= 0.0f || Y <= 0.0f) return glm::vec3(0.0f);
    const glm::vec3 rgb = xyzToRec709({x / y * Y, Y, (1.0f - x - y) / y * Y});
    return glm::max(rgb, glm::vec3(0.0f));
}

Image skyImage(const SkyParams& p, uint32_t width) {
    width = std::max(width, 4u);
    const uint32_t height = width / 2;
    Image img(width, height, 4);
    // Sky illuminance on the ground, ∫ L cos θ dω over the upper half (texel solid angle
    // (2π/w)(π/h) sin θ).
    glm::dvec3 skyE(0.0);
    for (uint32_t y = 0; y < height; ++y)
        for (uint32_t x = 0; x < width; ++x) {
            const glm::vec2 uv{(static_cast<float>(x) + 0.5f) / static_cast<float>(width),
                               (static_cast<float>(y) + 0.5f) / static_cast<float>(height)};
            const glm::vec3 d = equirectDirection(uv);
            if (d.y < 0.0f) continue;
            const glm::vec3 L = preethamSky(d, p);
            for (int c = 0; c < 3; ++c) img.at(x, y, static_cast<uint32_t>(c)) = L[c];
            img.at(x, y, 3) = 1.0f;
            const double dOmega =
                (2.0 * kPi / double(width)) * (kPi / double(height)) * std::sin(double(uv.y) * kPi);
            skyE += glm::dvec3(L) * static_cast<double>(d.y) * dOmega;
        }
    const glm::vec3 s = glm::normalize(p.toSun);
    const glm::vec3 sunE = glm::vec3(p.sunLux * std::max(s.y, 0.0f));
    const glm::vec3 ground = p.groundAlbedo * (sunE + glm::vec3(skyE)) / kPi;
    for (uint32_t y = 0; y < height; ++y)
        for (uint32_t x = 0; x < width; ++x) {
            const glm::vec3 d =
                equirectDirection({(static_cast<float>(x) + 0.5f) / static_cast<float>(width),
                                   (static_cast<float>(y) + 0.5f) / static_cast<float>(height)});
            if (d.y >= 0.0f) continue;
            for (int c = 0; c < 3; ++c) img.at(x, y, static_cast<uint32_t>(c)) = ground[c];
            img.at(x, y, 3) = 1.0f;
        }
    return img;
}

Result<Image> environmentImage(const Scene& scene, bool keepSun) {
    if (!scene.environment) return fail(ErrorCode::InvalidInput, "the scene has no environment");
    const Environment& e = *scene.environment;
    if (e.image && !keepSun) return *e.image;  // takeEnvironmentSun's (the file read once)
    const std::string what = "environment '" + e.name + "'";
    Image src;
    if (e.kind == "color") {
        src = Image(1, 1, 4);
        for (uint32_t c = 0; c < 3; ++c)
            src.at(0, 0, c) = e.color[static_cast<int>(c)] * e.intensity;
        src.at(0, 0, 3) = 1.0f;
        return src;
    }
    if (e.kind == "sky") {
        SkyParams p;
        p.turbidity = e.turbidity;
        for (const Light& l : scene.lights)
            if (l.type == LightType::Directional) {
                p.toSun = -glm::normalize(l.direction);
                p.sunLux = l.intensity;
                break;
            }
        Image img = skyImage(p, 512);
        for (size_t i = 0; i < img.pixels.size(); i += 4)
            for (size_t c = 0; c < 3; ++c) img.pixels[i + c] *= e.intensity;
        if (e.rotation == 0.0f) return img;
        src = std::move(img);
    } else {
        const bool exr = e.file.size() >= 4 && (e.file.substr(e.file.size() - 4) == ".exr" ||
                                                e.file.substr(e.file.size() - 4) == ".EXR");
        if (exr) {
            auto f = readExr(e.file);
            if (!f) return fail(f.error().code, what + ": " + f.error().message);
            if (f->layers.empty() || f->layers[0].image.channels < 3)
                return fail(ErrorCode::InvalidInput, what + ": '" + e.file + "' has no RGB layer");
            src = std::move(f->layers[0].image);
        } else {
            auto img = readHdr(e.file);
            if (!img) return fail(img.error().code, what + ": " + img.error().message);
            src = std::move(*img);
        }
        if (src.width < 2 || src.height < 1)
            return fail(ErrorCode::InvalidInput, what + ": '" + e.file + "' is " +
                                                     std::to_string(src.width) + "x" +
                                                     std::to_string(src.height) +
                                                     ", too small for an equirectangular image");
        for (float v : src.pixels)
            if (!std::isfinite(v) || v < 0.0f)
                return fail(ErrorCode::InvalidInput,
                            what + ": '" + e.file + "' holds a negative or non-finite value");
    }
    // Resample into world orientation (the rotation turns the image about +Y) and apply the intensity.
    const float scale = e.kind == "sky" ? 1.0f : e.intensity;
    Image out(src.width, src.height, 4);
    for (uint32_t y = 0; y < out.height; ++y)
        for (uint32_t x = 0; x < out.width; ++x) {
            glm::vec2 uv{(static_cast<float>(x) + 0.5f) / static_cast<float>(out.width),
                         (static_cast<float>(y) + 0.5f) / static_cast<float>(out.height)};
            uv.x -= e.rotation / (2.0f * kPi);
            uv.x -= std::floor(uv.x);
            const glm::vec3 L = sampleEquirect(src, uv) * scale;
            for (int c = 0; c < 3; ++c) out.at(x, y, static_cast<uint32_t>(c)) = L[c];
            out.at(x, y, 3) = 1.0f;
        }
    if (e.kind == "hdr" && e.sun != "keep" && !keepSun)
        if (auto sun = findEnvironmentSun(out)) removeEnvironmentSun(out, *sun);
    return out;
}

Result<void> chooseEnvironment(Scene& scene, const std::string& option, bool litByDefault) {
    Environment sky;
    sky.name = "sky";
    sky.kind = "sky";
    if (option.empty()) {
        if (litByDefault && scene.lights.empty() && !scene.environment) scene.environment = sky;
        return {};
    }
    if (option == "none") {
        scene.environment.reset();
        return {};
    }
    if (option == "sky") {
        scene.environment = sky;
        return {};
    }
    const std::string ext = option.size() >= 4 ? option.substr(option.size() - 4) : "";
    if (ext != ".hdr" && ext != ".exr" && ext != ".HDR" && ext != ".EXR")
        return fail(
            ErrorCode::InvalidInput,
            "--environment: expected an equirectangular .hdr or .exr file, 'sky' or 'none', got '" +
                option + "'");
    std::FILE* f = std::fopen(option.c_str(), "rb");
    if (!f) return fail(ErrorCode::NotFound, "--environment: cannot open '" + option + "'");
    std::fclose(f);
    Environment e;
    e.name = option;
    e.kind = "hdr";
    e.file = option;
    scene.environment = e;
    scene.files.push_back(option);
    return {};
}

EnvironmentCdf environmentCdf(const Image& equirect, uint32_t width, uint32_t height) {
    EnvironmentCdf cdf;
    cdf.width = width;
    cdf.height = height;
    cdf.data.assign(height + 1 + size_t(height) * (width + 1) + size_t(width) * height, 0.0f);
    // Mean luminance (Rec.709 Y) of the image's texels in each cell (nearest cell for an image
    // smaller than the grid).
    std::vector<double> sum(size_t(width) * height, 0.0);
    std::vector<uint32_t> count(size_t(width) * height, 0);
    double total = 0.0;
    const uint32_t channels = equirect.channels;
    for (uint32_t y = 0; y < equirect.height; ++y)
        for (uint32_t x = 0; x < equirect.width; ++x) {
            const float* px = &equirect.pixels[equirect.index(x, y, 0)];
            const double lum =
                channels >= 3 ? 0.2126 * px[0] + 0.7152 * px[1] + 0.0722 * px[2] : px[0];
            const uint32_t cx = std::min(width - 1, uint32_t((x + 0.5) * width / equirect.width));
            const uint32_t cy =
                std::min(height - 1, uint32_t((y + 0.5) * height / equirect.height));
            sum[size_t(cy) * width + cx] += std::max(lum, 0.0);
            ++count[size_t(cy) * width + cx];
            total += std::max(lum, 0.0);
        }
    const double mean = equirect.width * equirect.height > 0
                            ? total / (double(equirect.width) * equirect.height)
                            : 0.0;
    const double floor = std::max(1e-3 * mean, 1e-12);
    std::vector<double> cellMean(size_t(width) * height, 0.0);
    for (size_t i = 0; i < cellMean.size(); ++i) cellMean[i] = count[i] ? sum[i] / count[i] : 0.0;
    // Each cell takes the brightest mean of itself and its eight neighbours (wrapping around in
    // longitude): the renderer reads the image bilinearly, so a bright texel lights the half texel
    // around it too, and that ring must not have a dim cell's density (its few samples would be
    // fireflies).
    std::vector<double> weight(size_t(width) * height);
    std::vector<double> rowWeight(height, 0.0);
    for (uint32_t r = 0; r < height; ++r) {
        const double sinTheta = std::sin((r + 0.5) / height * M_PI);
        for (uint32_t c = 0; c < width; ++c) {
            double brightest = 0.0;
            for (int dr = -1; dr <= 1; ++dr) {
                const int rr = int(r) + dr;
                if (rr < 0 || rr >= int(height)) continue;
                for (int dc = -1; dc <= 1; ++dc) {
                    const uint32_t cc = (c + width + uint32_t(dc + 1) - 1u) % width;
                    brightest = std::max(brightest, cellMean[size_t(rr) * width + cc]);
                }
            }
            const size_t i = size_t(r) * width + c;
            weight[i] = (brightest + floor) * sinTheta;
            rowWeight[r] += weight[i];
        }
    }
    double all = 0.0;
    for (double w : rowWeight) all += w;
    double running = 0.0;
    for (uint32_t r = 0; r < height; ++r) {
        cdf.data[r] = static_cast<float>(running / all);
        running += rowWeight[r];
        double inRow = 0.0;
        for (uint32_t c = 0; c < width; ++c) {
            cdf.data[cdf.conditional(r) + c] = static_cast<float>(inRow / rowWeight[r]);
            inRow += weight[size_t(r) * width + c];
            cdf.data[cdf.cell(c, r)] = static_cast<float>(weight[size_t(r) * width + c] / all);
        }
        cdf.data[cdf.conditional(r) + width] = 1.0f;
    }
    cdf.data[height] = 1.0f;
    return cdf;
}

namespace {
// The last index i in [0, n) with cdf[i] <= u (cdf ascending from 0).
uint32_t findInterval(const float* cdf, uint32_t n, float u) {
    uint32_t lo = 0, hi = n;
    while (hi - lo > 1) {
        const uint32_t mid = (lo + hi) / 2;
        if (cdf[mid] <= u)
            lo = mid;
        else
            hi = mid;
    }
    return lo;
}
}  // namespace

glm::vec3 EnvironmentCdf::sample(glm::vec2 u, float& density) const {
    const uint32_t r = findInterval(data.data(), height, u.y);
    const float r0 = data[r], r1 = data[r + 1];
    const float fy = r1 > r0 ? (u.y - r0) / (r1 - r0) : 0.5f;
    const float* row = data.data() + conditional(r);
    const uint32_t c = findInterval(row, width, u.x);
    const float fx = row[c + 1] > row[c] ? (u.x - row[c]) / (row[c + 1] - row[c]) : 0.5f;
    const float w = static_cast<float>(width), h = static_cast<float>(height);
    const glm::vec2 uv((static_cast<float>(c) + std::clamp(fx, 0.0f, 1.0f)) / w,
                       (static_cast<float>(r) + std::clamp(fy, 0.0f, 1.0f)) / h);
    const glm::vec3 d = equirectDirection(uv);
    // The drawn cell's density at the sample's own θ (not pdf(d): mapping d back through acos can
    // land an edge sample in the neighbouring cell).
    density = cellDensity(c, r, std::sin(uv.y * float(M_PI)));
    return d;
}

float EnvironmentCdf::pdf(glm::vec3 direction) const {
    const glm::vec2 uv = equirectUv(direction);
    const float w = static_cast<float>(width), h = static_cast<float>(height);
    const uint32_t c = std::min(width - 1, uint32_t(std::max(uv.x - std::floor(uv.x), 0.0f) * w));
    const uint32_t r = std::min(height - 1, uint32_t(std::clamp(uv.y, 0.0f, 1.0f) * h));
    return cellDensity(c, r, std::sin(std::clamp(uv.y, 0.0f, 1.0f) * float(M_PI)));
}

float EnvironmentCdf::cellDensity(uint32_t column, uint32_t row, float sinTheta) const {
    if (sinTheta <= 0.0f) return 0.0f;
    return data[cell(column, row)] * static_cast<float>(width) * static_cast<float>(height) /
           (2.0f * float(M_PI) * float(M_PI) * sinTheta);
}

}  // namespace rg

// The distant light probe's source (seed 002 §4.9.1.1): a scene's environment as one
// equirectangular image of luminance in cd/m² (nits), in world orientation, which the GPU scene
// uploads and the pipeline's environment passes filter (scripts/ibl.lua). Three kinds:
// - "hdr": an equirectangular .hdr or .exr, times `intensity`, turned by `rotation` about +Y;
// - "color": a uniform colour × intensity (the white furnace);
// - "sky": Preetham's clear-sky model (below) lit by the scene's sun: same direction, and the sky's
//   luminance scaled with the sun's illuminance, so sky and sun light agree.
//
// Mapping (the same in shaders/lib/environment.glsl): direction d (unit, +Y up) ↔ texel
//   u = 0.5 + atan(d.x, -d.z) / 2π,  v = acos(d.y) / π   (v = 0 at the zenith, top row first),
// so the image's centre column looks down −Z, its left quarter −X.
// Pure functions, thread-safe; no Vulkan.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "core/result.h"
#include "image/image.h"
#include "scene.h"

namespace rg {

glm::vec2 equirectUv(glm::vec3 direction);
glm::vec3 equirectDirection(glm::vec2 uv);
// Bilinear lookup of an equirectangular image's RGB at uv, wrapping in u and clamped in v (the seam).
glm::vec3 sampleEquirect(const Image& img, glm::vec2 uv);

// The clear-sky sun that Preetham's zenith luminance goes with: direct illuminance perpendicular
// to the rays for a high sun on a clear day — seed 000 tbl:11 measured 106 500 to 123 100 lux
// around midday; with 120 000 the sky's illuminance on the ground lands within the table's sky
// column (tests/unit/test_environment.cpp). A scene sun of E lux scales the sky by E / kClearSkySunLux.
inline constexpr float kClearSkySunLux = 120000.0f;

struct SkyParams {
    glm::vec3 toSun{0.0f, 0.70710678f, 0.70710678f};  // unit, towards the sun
    float turbidity = 2.5f;                           // Preetham's T, 2 (very clear) .. 10 (hazy)
    float sunLux = kClearSkySunLux;  // the scene's sun, lux perpendicular to its rays
    float groundAlbedo = 0.2f;       // the ground under the horizon (Lambertian)
};

// Preetham, Shirley & Smits, "A Practical Analytic Model for Daylight" (1999): Perez's luminance
// distribution with the paper's turbidity fits for Y, x and y, the zenith luminance (kcd/m²) and
// chromaticity; xyY → linear Rec.709. Returns cd/m² for a direction above the horizon (y ≥ 0).
glm::vec3 preethamSky(glm::vec3 direction, const SkyParams& p);

// A width × (width/2) equirectangular image (RGBA, nits) of the sky over a ground: above the
// horizon preethamSky; below it a Lambertian ground of groundAlbedo lit by the sun and by the sky
// (its illuminance integrated from the image's own upper half): L = ρ (E_sun + E_sky) / π.
Image skyImage(const SkyParams& p, uint32_t width = 512);

// The scene's environment as an RGBA equirectangular image in nits (width ≥ 1), its sun taken
// out unless its `sun` mode is "keep" (findEnvironmentSun). No environment: none (the caller
// binds black). The sky takes its sun from the scene's first sun light (default:
// 45° up, from +Z, kClearSkySunLux). Errors name the environment and the file. `keepSun` leaves
// an "hdr" image's sun in whatever its mode. Environment::image, when takeEnvironmentSun kept one,
// is returned as it is.
Result<Image> environmentImage(const Scene& scene, bool keepSun = false);

// A piecewise-constant importance-sampling distribution of an equirectangular environment over a
// grid of width × height cells (the reference mode's environment samples, shaders/passes/
// reference.comp): each cell's probability ∝ (the largest mean luminance of it and its eight
// neighbours — the image is read bilinearly — + 1e-3 of the image's mean) × sin θ at its centre; a sample picks a cell by the marginal (rows) then the conditional (columns)
// CDF and a uniform point inside it, so the density over the unit square is
// cellProbability · width · height and over the sphere that / (2π² sin θ). Flat layout (the GPU's):
// rows + 1 marginal CDF values, then rows × (columns + 1) conditional CDF values, then
// rows × columns cell probabilities.
struct EnvironmentCdf {
    uint32_t width = 0, height = 0;
    std::vector<float> data;
    size_t conditional(uint32_t row) const { return height + 1 + size_t(row) * (width + 1); }
    size_t cell(uint32_t column, uint32_t row) const {
        return height + 1 + size_t(height) * (width + 1) + size_t(row) * width + column;
    }
    // The solid-angle density of a direction in cell (column, row) at polar angle θ (sin θ given).
    float cellDensity(uint32_t column, uint32_t row, float sinTheta) const;
    // A direction from two uniform numbers in [0, 1), and its solid-angle density.
    glm::vec3 sample(glm::vec2 u, float& pdf) const;
    float pdf(glm::vec3 direction) const;
};
EnvironmentCdf environmentCdf(const Image& equirect, uint32_t width = 256, uint32_t height = 128);

// A sun in an equirectangular environment image (seed 002 §4.9.1.1: the strong sources are taken
// out of the distant probe and lit as lights). Found from the brightest texel: the texels
// connected to it (8-neighbours, wrapping in longitude) whose luminance exceeds kSunHotContrast ×
// the image's mean (the GPU's env_hot rule) are the sun; they are refilled with the radiance of
// the ring just outside them, and what they held above it is the sun's light.
struct EnvironmentSun {
    glm::vec3 toSun{0.0f, 1.0f, 0.0f};  // unit: the excess luminance's centroid direction
    glm::vec3 illuminance{0.0f};  // lux perpendicular to the rays, RGB: Σ (L − fill) Ω per channel
    // Radians: the uniform disk of the same angular spread about toSun (a disk of radius r has
    // ⟨θ²⟩ = r² / 2), at least the real sun's 0.2664° when the image cannot resolve it.
    float angularRadius = 0.0f;
    float solidAngle = 0.0f;       // steradians the taken texels cover
    glm::vec3 fill{0.0f};          // the radiance they are given: the mean of the ring around them
    float peakNits = 0.0f;         // the brightest texel's luminance
    std::vector<uint32_t> texels;  // y · width + x of each taken texel
};
inline constexpr float kSunHotContrast = 20.0f;     // region: luminance > 20 × the mean
inline constexpr float kSunPeakContrast = 1000.0f;  // a sun: the peak > 1000 × the mean
inline constexpr float kSunMaxSolidAngle = 0.05f;   // sr (a disk of ~7.2°): larger is no sun
// None when the peak is under kSunPeakContrast × the mean or the region covers more than
// kSunMaxSolidAngle (an overcast sky's bright patch, a window). Deterministic, one pass.
std::optional<EnvironmentSun> findEnvironmentSun(const Image& equirect);
// Writes the sun's fill over its texels (the image findEnvironmentSun was given).
void removeEnvironmentSun(Image& equirect, const EnvironmentSun& sun);

// The environment's sun as its `sun` mode says (scene.h Environment::sun): with "light" (or
// "auto" and no sun light in the scene) appends a sun light named "<environment> sun" of the
// found direction, illuminance (its colour the illuminance's chromaticity) and angular radius,
// marked fromEnvironment; environmentImage takes the texels out for every mode but "keep".
// Returns a line saying what was done ("" when nothing: no "hdr" environment, "keep", no sun,
// or already taken). Errors are environmentImage's.
Result<std::string> takeEnvironmentSun(Scene& scene);

// The environment a render uses (the --environment option): "" keeps the scene's — except that,
// with `litByDefault` (a glTF file, as published), a scene with no light and no environment gets
// the sky, so that it is lit as in any glTF viewer; "sky" the Preetham sky of the scene's sun;
// "none" no environment; anything else an equirectangular .hdr/.exr file of nits (it must exist).
Result<void> chooseEnvironment(Scene& scene, const std::string& option, bool litByDefault);

}  // namespace rg

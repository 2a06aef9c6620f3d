// The image-based half of `rgraph accuracy` (--ibl): the distant probe's filtering
// (scripts/ibl.lua, seed 002 §4.9.2) against integrals computed here on the CPU from the very cube
// the filter reads (env_source, mip 0, every texel with its exact solid angle), so that what is
// measured is the filtering alone:
// - the diffuse probe: env_sh's order-2 irradiance (as lib/environment.glsl evaluates it) against
//   Σ L (n·l)⁺ Ω;
// - each mip of env_specular against the split sum's own definition with v = n,
//   ∫ L(l) D(h) (n·l) dl / ∫ D(h) (n·l) dl;
// - the DFG table against lighting/brdf.h's integrators.
// Green channel throughout (relative errors of a grey measure).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "core/result.h"
#include "image/image.h"
#include "runtime/runtime.h"

namespace rg {

struct IblAccuracyOptions {
    // Equirectangular .hdr/.exr files, "sky" (the Preetham sky of the default sun) or "synthetic"
    // (writeSyntheticSunSky: a sun of 4·10⁴ nits over 10 nits).
    std::vector<std::string> environments = {"synthetic", "sky"};
    // The environment's sun mode (scene.h Environment::sun): "keep" measures the probe with the
    // sun in it, the hard case the hot texels are for.
    std::string sun = "keep";
    uint32_t directionsPerFace = 4;  // n × n directions of each cube face, per mip
    std::string scratchDir;          // where "synthetic" is written ("" = the system's temp)
    std::function<void(const std::string& name, size_t index, size_t count)> progress;
};

// Bounds: the (pre-filter within 5 % wherever the cube resolves the lobe; SH within 10 %
// where the irradiance is at least a quarter of its peak) and the DFG's 0.01 (seed values).
inline constexpr double kIblPrefilterBound = 0.05;       // worst, resolved mips
inline constexpr double kIblUnresolvedMeanBound = 0.02;  // mean, mips narrower than two texels
inline constexpr double kIblShLitBound = 0.10;
inline constexpr double kIblDfgBound = 0.01;

struct IblMipAccuracy {
    uint32_t mip = 0;
    double linearRoughness = 0.0;
    double worst = 0.0, mean = 0.0;  // relative error over the directions
    bool resolved = true;            // the lobe spans at least two source texels
    Image error;                     // 6n × n, the faces side by side (+X −X +Y −Y +Z −Z)
    bool pass() const {
        return resolved ? worst <= kIblPrefilterBound : mean <= kIblUnresolvedMeanBound;
    }
};

struct IblEnvironmentAccuracy {
    std::string name;
    double peakIrradiance = 0.0;               // lux (green)
    double shLitWorst = 0.0;                   // directions ≥ 1/4 of the peak
    double shDimWorst = 0.0, shDimMean = 0.0;  // the others (facing away from a sun)
    size_t shLit = 0, shDim = 0;
    Image shError;  // 6n × n
    std::vector<IblMipAccuracy> mips;
    bool pass() const;
};

struct IblAccuracy {
    std::vector<IblEnvironmentAccuracy> environments;
    double dfgWorst = 0.0;  // |table − integrator| over the texels checked
    size_t dfgTexels = 0;
    bool pass() const;
};

// A 1024 × 512 equirectangular EXR of 10 nits with a 0.5° sun of 4·10⁴ nits (the most a
// half-float cube holds) 40° up, its edge sampled 4 × 4 per texel.
Result<void> writeSyntheticSunSky(const std::string& path);

Result<IblAccuracy> runIblAccuracy(Runtime& runtime, const IblAccuracyOptions& options);

std::string iblAccuracyTable(const IblAccuracy& result);
// DIR/index.html with the tables and a heat map per environment and mip (DIR/<env>_*.png).
Result<void> writeIblAccuracyReport(const IblAccuracy& result, const std::string& dir);

}  // namespace rg

// The area-light accuracy suite (rgraph accuracy; seed 000 §2.3's reference mode as the judge):
// every area light type × {facing, grazing, horizon-crossing} × {rough dielectric, glossy
// dielectric, glossy metal} on scripts/scenes/accuracy.lua, rendered by the real-time pipeline
// (deferred.lua, one frame) and by the reference mode (reference.lua, accumulated in two
// independent halves with different seeds), compared over the pixels the reference lights above
// 1 % of its peak.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "core/result.h"
#include "image/image.h"
#include "runtime/runtime.h"

namespace rg {

struct AccuracyOptions {
    uint32_t width = 160, height = 120;
    uint32_t frames = 64;  // reference frames per half
    uint32_t samples =
        4;  // samples per pixel per reference frame (reference.lua's reference_samples)
    std::vector<std::string> lights = {"sphere", "disk", "rect", "tube"};
    std::vector<std::string> placements = {"facing", "grazing", "horizon"};
    std::vector<std::string> materials = {"rough", "glossy", "metal"};
    // The area-light models measured (scripts/lighting.lua's area_lights), each against the same reference.
    std::vector<std::string> models = {"frostbite", "ltc"};
    std::function<void(const std::string& caseName, size_t index, size_t count)> progress;
};

struct AccuracyCase {
    std::string light, placement, material, model;
    double meanError = 0.0;       // mean |rt − ref| / ref over the lit pixels (RGB)
    double p95Error = 0.0;        // its 95th percentile
    double energyError = 0.0;     // Σ rt / Σ ref − 1
    double referenceNoise = 0.0;  // the reference's own: mean |a − b| / (a + b) of its two halves
    size_t pixels = 0;
    Image realtime, reference;  // luminance, cd/m² (RGBA)
    Image error;                // per pixel relative error (1 channel; 0 where unlit)
    std::string name() const {
        return light + " " + placement + " " + material + (model.empty() ? "" : " " + model);
    }
};

Result<std::vector<AccuracyCase>> runAccuracy(Runtime& runtime, const AccuracyOptions& options);

// The table as text (one line per case) and a page with the table and a heat map per case
// (`dir`/index.html, `dir`/<case>.png).
std::string accuracyTable(const std::vector<AccuracyCase>& cases);
Result<void> writeAccuracyReport(const std::vector<AccuracyCase>& cases, const std::string& dir);

}  // namespace rg

#include "photometry.h"

#include <cmath>

namespace rg::photometry {

double ev100FromCamera(double aperture, double shutterSeconds, double iso, double compensation) {
    return std::log2(aperture * aperture / shutterSeconds * 100.0 / iso) - compensation;
}

double ev100FromLuminance(double averageLuminance) {
    return std::log2(averageLuminance * 100.0 / kMeterCalibration);
}

double luminanceFromEv100(double ev100) { return std::exp2(ev100) * kMeterCalibration / 100.0; }

double exposureFromEv100(double ev100) {
    const double maxLuminance = kSaturationConstant / (100.0 * kLensAttenuation) * std::exp2(ev100);
    return 1.0 / maxLuminance;
}

double bloomLuminance(double color, double bloomCompensation, double currentEv100) {
    return color * std::exp2(currentEv100 + bloomCompensation - 3.0);
}

}  // namespace rg::photometry

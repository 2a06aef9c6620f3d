// What the golden-test machinery tests (tests/unit/test_metrics.cpp, test_metrics_golden.cpp)
// share: a uniform image and a comparison of one metric.
#pragma once

#include <algorithm>
#include <cstdint>

#include "golden/metrics.h"
#include "image/image.h"

namespace rg::test {

inline Image filled(uint32_t w, uint32_t h, uint32_t c, float v) {
    Image img(w, h, c);
    std::fill(img.pixels.begin(), img.pixels.end(), v);
    return img;
}

inline golden::Comparison with(golden::Metric m, double tolerance) {
    golden::Comparison c;
    c.metric = m;
    c.tolerance = tolerance;
    return c;
}

}  // namespace rg::test

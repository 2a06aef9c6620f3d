// `rgraph compare`: the error between two EXR renders.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "golden/metrics.h"
#include "cli.h"

namespace rg::cli {

namespace {

const char* const kHelp =
    "usage: rgraph compare A.exr B.exr [--layer NAME] [--heatmap FILE.png] [--tolerance T]\n"
    "                      [--downsample N]\n\n"
    "Compares layer NAME (default 'hdr', else the first layer) of A against B (the reference): "
    "mean and\n"
    "max relative error |a - b| / max(|b|, 1e-3), RMSE and PSNR (peak: B's maximum), over RGB. "
    "--heatmap\n"
    "writes the per-pixel relative error as a colour map (black 0, white >= the max). With "
    "--tolerance,\n"
    "exits 1 when the mean relative error exceeds it. --downsample N: B is a supersampled render, "
    "N times\n"
    "A's width and height, box-filtered to A's size (the mean of its N x N texels, in its "
    "linear values)\n"
    "before the comparison.\n";

// The mean of each n x n block of `image` (its width and height multiples of n).
Image boxDownsample(const Image& image, uint32_t n) {
    Image out(image.width / n, image.height / n, image.channels);
    const float scale = 1.0f / static_cast<float>(n * n);
    for (uint32_t y = 0; y < image.height; ++y)
        for (uint32_t x = 0; x < image.width; ++x)
            for (uint32_t c = 0; c < image.channels; ++c)
                out.pixels[(size_t(y / n) * out.width + x / n) * out.channels + c] +=
                    image.pixels[(size_t(y) * image.width + x) * image.channels + c] * scale;
    return out;
}

}  // namespace

int cmdCompare(int argc, char** argv) {
    using namespace rg::golden;
    Args args;
    if (auto done = parseCommand(argc, argv, "compare",
                                 {"layer", "heatmap", "tolerance", "downsample"}, kHelp, args))
        return *done;
    const auto files = args.all("");
    if (files.size() != 2)
        return usageError("give two EXR files: the image and the reference", "compare");
    auto a = readExr(files[0]);
    if (!a) return report(a.error());
    auto b = readExr(files[1]);
    if (!b) return report(b.error());
    auto pick = [&](const ExrFile& f, const std::string& file) -> Result<Image> {
        const std::string want = args.get("layer", "hdr");
        for (const auto& l : f.layers)
            if (l.name == want) return l.image;
        if (!args.has("layer") && !f.layers.empty()) return f.layers.front().image;
        return fail(ErrorCode::NotFound, "'" + file + "' has no layer '" + want + "'");
    };
    auto ia = pick(*a, files[0]);
    if (!ia) return report(ia.error());
    auto ib = pick(*b, files[1]);
    if (!ib) return report(ib.error());
    if (args.has("downsample")) {
        const std::string v = args.get("downsample");
        char* end = nullptr;
        const long n = std::strtol(v.c_str(), &end, 10);
        if (end == v.c_str() || *end != '\0' || n < 1 || n > 64)
            return usageError("--downsample: expected a whole number 1..64, got '" + v + "'",
                              "compare");
        const uint32_t f = static_cast<uint32_t>(n);
        if (ib->width != ia->width * f || ib->height != ia->height * f)
            return usageError("--downsample " + v + ": '" + files[1] + "' is " +
                                  std::to_string(ib->width) + "x" + std::to_string(ib->height) +
                                  ", not " + v + " times " + std::to_string(ia->width) + "x" +
                                  std::to_string(ia->height),
                              "compare");
        ib = boxDownsample(*ib, f);
    }
    std::vector<uint32_t> rgb;
    for (uint32_t c = 0; c < std::min(3u, ib->channels); ++c) rgb.push_back(c);
    float peak = 0;
    for (float v : ib->pixels) peak = std::max(peak, v);
    std::map<std::string, MetricResult> results;
    for (Metric m : {Metric::RelMean, Metric::RelMax, Metric::Rmse, Metric::Psnr}) {
        Comparison c;
        c.metric = m;
        c.channels = rgb;
        c.peak = peak > 0 ? peak : 1.0;
        auto r = compare(*ia, *ib, c);
        if (!r) return report(r.error());
        results[metricName(m)] = *r;
    }
    std::printf("rgraph compare: %s vs %s (%ux%u)\n", files[0].c_str(), files[1].c_str(), ib->width,
                ib->height);
    std::printf(
        "  mean relative error %s\n  max relative error  %s (%s)\n  RMSE                %s\n  PSNR "
        "               %s dB\n",
        formatNumber(results["rel_mean"].value).c_str(),
        formatNumber(results["rel_max"].value).c_str(), results["rel_max"].detail.c_str(),
        formatNumber(results["rmse"].value).c_str(), formatNumber(results["psnr"].value).c_str());
    if (args.has("heatmap")) {
        const MetricResult& rel = results["rel_max"];
        Image map = heatMap(rel.error, static_cast<float>(std::max(rel.value, 1e-6)));
        if (auto r = writePng(args.get("heatmap"), map); !r) return report(r.error());
        std::printf("  heat map: %s\n", args.get("heatmap").c_str());
    }
    if (args.has("tolerance")) {
        const double t = std::strtod(args.get("tolerance").c_str(), nullptr);
        if (results["rel_mean"].value > t) {
            std::printf("rgraph compare: mean relative error above the tolerance %s\n",
                        formatNumber(t).c_str());
            return kFailed;
        }
    }
    return kOk;
}

}  // namespace rg::cli

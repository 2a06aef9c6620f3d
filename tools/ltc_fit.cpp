// rgraph-ltc-fit: fits the linearly-transformed-cosine table of graph/lighting/ltc.h to the GGX
// lobe of shaders/lib/brdf.glsl and writes it as C++ initialisers
// (graph/lighting/ltc_ggx.inc, the committed table). Each roughness column is fitted from the
// normal view (NdotV = 1) towards grazing, every cell starting from its neighbour's fit; columns
// run in parallel. Prints the fit's L1 distance to the lobe (ltc::fitDistance) over the table.
//
//   build/tools/rgraph-ltc-fit [--samples N] [--out FILE]     (default 32, graph/lighting/ltc_ggx.inc)
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "lighting/ltc.h"

using namespace rg;

int main(int argc, char** argv) {
    int samples = 32;
    std::string out = std::string(RG_SOURCE_ROOT) + "/graph/lighting/ltc_ggx.inc";
    for (int i = 1; i < argc; ++i) {
        if (!std::strcmp(argv[i], "--samples") && i + 1 < argc)
            samples = std::max(4, std::atoi(argv[++i]));
        else if (!std::strcmp(argv[i], "--out") && i + 1 < argc)
            out = argv[++i];
        else {
            std::fprintf(stderr, "usage: rgraph-ltc-fit [--samples N] [--out FILE]\n");
            return 2;
        }
    }
    const int n = ltc::kSize;
    struct Cell {
        ltc::Fit fit;
        double distance = 0;
    };
    std::vector<Cell> cells(size_t(n) * n);
    std::atomic<int> next{0}, done{0};
    std::mutex print;
    const auto t0 = std::chrono::steady_clock::now();
    auto worker = [&] {
        for (int col; (col = next.fetch_add(1)) < n;) {
            const float linearRoughness = float(col) / float(n - 1);
            glm::dvec4 p;
            for (int row = 0; row < n; ++row) {
                const float y = float(row) / float(n - 1);
                const float NdotV = std::max(1.0f - y * y, 1e-3f);
                Cell& c = cells[size_t(row) * n + size_t(col)];
                c.fit = ltc::fitCell(linearRoughness, NdotV, row ? &p : nullptr, &p, samples);
                c.distance = ltc::fitDistance(linearRoughness, NdotV,
                                              ltc::inverseMatrix(c.fit.entry.inverse));
            }
            std::lock_guard lock(print);
            const double s =
                std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
            std::fprintf(stderr, "rgraph-ltc-fit: roughness column %d/%d (%.0f s)\n", ++done, n, s);
        }
    };
    std::vector<std::thread> threads;
    const unsigned count = std::max(1u, std::thread::hardware_concurrency());
    for (unsigned t = 0; t < count; ++t) threads.emplace_back(worker);
    for (auto& t : threads) t.join();

    std::FILE* f = std::fopen(out.c_str(), "w");
    if (!f) {
        std::fprintf(stderr, "rgraph-ltc-fit: cannot write %s\n", out.c_str());
        return 1;
    }
    std::fprintf(f,
                 "// Fitted by tools/ltc_fit.cpp (build/tools/rgraph-ltc-fit --samples %d): do not "
                 "edit. graph/lighting/ltc.h\n"
                 "// says what each entry holds: {a, b, c, d, magnitude, fresnel}, row-major over\n"
                 "// (sqrt(1 - NdotV), linearRoughness), %d x %d.\n",
                 samples, n, n);
    for (const Cell& c : cells) {
        const ltc::Entry& e = c.fit.entry;
        std::fprintf(f, "{%.9g, %.9g, %.9g, %.9g, %.9g, %.9g},\n", e.inverse[0], e.inverse[1],
                     e.inverse[2], e.inverse[3], e.magnitude, e.fresnel);
    }
    std::fclose(f);
    double mean = 0, worst = 0;
    for (const Cell& c : cells)
        mean += c.distance / double(cells.size()), worst = std::max(worst, c.distance);
    std::fprintf(stderr,
                 "rgraph-ltc-fit: wrote %s\nL1 distance of the fit to the lobe (0 exact, 2 "
                 "disjoint): mean %.4f, worst %.4f;\n"
                 "rows: linearRoughness, columns: NdotV from 1 to grazing\n",
                 out.c_str(), mean, worst);
    for (int col = 0; col < n; col += 9) {
        std::fprintf(stderr, "  %.2f:", float(col) / float(n - 1));
        for (int row = 0; row < n; row += 9)
            std::fprintf(stderr, " %.3f", cells[size_t(row) * n + size_t(col)].distance);
        std::fprintf(stderr, "\n");
    }
    return 0;
}

// Inside compile(): the state its steps share (Compiler), the helpers two steps use, and the
// steps, one file each: compiler_validate.cpp, compiler_cull.cpp (cull, schedule),
// compiler_lifetimes.cpp (lifetimes, alias), compiler_barriers.cpp. Internal to graph/core.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

#include "compiler.h"

namespace rg::compiler_steps {

// Texture dimensions beyond this are a typo in a script, not a render target.
constexpr uint32_t kMaxDimension = 65536;

inline uint64_t alignUp(uint64_t v, uint64_t a) { return a <= 1 ? v : (v + a - 1) / a * a; }

struct Extent {
    uint32_t width = 0;
    uint32_t height = 0;
};

// OutputRelative: max(1, floor(output * scale)); Absolute: as declared.
inline uint32_t scaledDimension(uint32_t output, float scale) {
    const double v = std::floor(static_cast<double>(output) * static_cast<double>(scale));
    if (!(v >= 1.0)) return 1;
    if (v > static_cast<double>(kMaxDimension) * 4.0) return kMaxDimension * 4;
    return static_cast<uint32_t>(v);
}

inline Extent resolveExtent(const TextureDesc& t, const CompileOptions& o) {
    if (t.sizeMode == SizeMode::Absolute) return {t.width, t.height};
    return {scaledDimension(o.outputWidth, t.scaleX), scaledDimension(o.outputHeight, t.scaleY)};
}

// floor(log2(max(w, h))) + 1
inline uint32_t fullMipChain(Extent e) {
    uint32_t m = std::max(e.width, e.height);
    uint32_t n = 0;
    for (; m != 0; m >>= 1) ++n;
    return std::max(n, 1u);
}

inline std::string withOrigin(const std::string& origin, std::string text) {
    return origin.empty() ? text : origin + ": " + text;
}

// The layout a texture usage needs (compiler_barriers.cpp); validation compares them too.
Layout usageLayout(Usage u, PassType type);

// All accesses of one pass to one resource, folded together (barriers are per resource).
struct MergedAccess {
    uint32_t resource = 0;  // GraphDesc::resources index
    bool reads = false;
    bool writes = false;
};

struct Compiler {
    const GraphDesc& graph;
    const CompileOptions& options;
    Plan plan;

    std::unordered_map<std::string, uint32_t> resourceIndex;  // name -> GraphDesc::resources index
    std::unordered_map<std::string, uint32_t> passIndex;      // name -> GraphDesc::passes index

    std::vector<std::vector<uint32_t>> accessResource;  // [pass][access] -> resource desc index
    std::vector<std::vector<MergedAccess>> merged;      // [pass] in first-access order
    std::vector<std::vector<uint32_t>> successors;      // every ordering edge u -> v (u runs first)
    std::vector<std::vector<uint32_t>> needs;  // v -> u where v needs u's work (RAW, WAW, after)
    std::vector<bool> kept;
    std::vector<uint32_t> order;        // scheduled pass desc indices
    std::vector<int32_t> planResource;  // resource desc index -> Plan::resources index
    std::vector<std::vector<uint32_t>>
        aliasPreds;                  // plan resource -> earlier occupants of its memory
    std::vector<int32_t> aliasFrom;  // plan resource -> most recent earlier occupant

    Compiler(const GraphDesc& g, const CompileOptions& o) : graph(g), options(o) {}

    std::string fieldOf(uint32_t pass, uint32_t access) const {
        const Access& a = graph.passes[pass].accesses[access];
        return a.field.empty() ? "accesses[" + std::to_string(access) + "]" : a.field;
    }
    std::string passError(uint32_t pass, const std::string& text) const {
        return withOrigin(graph.passes[pass].origin, text);
    }
    void addEdge(uint32_t from, uint32_t to, bool need) {
        successors[from].push_back(to);
        if (need) needs[to].push_back(from);
    }
};

using Status = Result<void>;

// The steps, in the order compile() runs them.
Status validate(Compiler& c);
void cull(Compiler& c);
void schedule(Compiler& c);
void computeLifetimes(Compiler& c);
void alias(Compiler& c);
void planBarriers(Compiler& c);

}  // namespace rg::compiler_steps

// Property test of compile(): thousands of random graphs (fixed seed), each compiled plan checked
// against invariants recomputed here from the declarations, independently of the compiler.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "core/compiler.h"

namespace {

using namespace rg;

struct GenOptions {
    uint32_t minPasses = 2;
    uint32_t maxPasses = 40;
    // Chance of each deliberate mistake (unordered writer, forward `after`, disabled pass, reuse
    // in one pass); 0 makes graphs that always compile.
    double mistakes = 0.003;
    double forwardAfter = 0.01;  // per pass; valid unless it closes a cycle
};

class GraphGenerator {
public:
    explicit GraphGenerator(uint32_t seed) : m_rng(seed) {}

    GraphDesc generate(const GenOptions& o) {
        GraphDesc g;
        const uint32_t passCount = range(o.minPasses, o.maxPasses);
        const uint32_t resourceCount = range(2, std::max(3u, passCount / 2 + 3));
        m_sizeClass.clear();
        for (uint32_t i = 0; i < resourceCount; ++i) g.resources.push_back(makeResource(i));

        std::vector<int32_t> lastWriter(resourceCount, -1);
        for (uint32_t pi = 0; pi < passCount; ++pi) {
            PassDesc p;
            p.name = "p" + std::to_string(pi);
            const double t = unit();
            p.type = t < 0.5 ? PassType::Raster : t < 0.85 ? PassType::Compute : PassType::Transfer;
            p.kind = passTypeName(p.type);
            p.sideEffect = chance(0.08);
            p.enabled = !chance(o.mistakes);
            std::vector<uint32_t> touched;

            // Reads of what is already there.
            const uint32_t reads = range(0, 3);
            for (uint32_t k = 0; k < reads; ++k) {
                std::vector<uint32_t> readable;
                const bool readAnything = chance(o.mistakes);
                for (uint32_t r = 0; r < resourceCount; ++r)
                    if ((lastWriter[r] >= 0 || g.resources[r].imported || readAnything) &&
                        std::find(touched.begin(), touched.end(), r) == touched.end())
                        readable.push_back(r);
                if (readable.empty()) break;
                const uint32_t r = pick(readable);
                Access a;
                a.resource = g.resources[r].name;
                a.usage = readUsage(g.resources[r], p.type);
                // One depth attachment per raster pass: further depth reads are sampled.
                if (a.usage == Usage::DepthStencilRead &&
                    std::any_of(p.accesses.begin(), p.accesses.end(),
                                [](const Access& x) { return x.usage == Usage::DepthStencilRead; }))
                    a.usage = Usage::Sampled;
                p.accesses.push_back(a);
                touched.push_back(r);
            }

            // Writes: raster attachments share one size class.
            const uint32_t writes = range(0, 2);
            const uint32_t sizeClass = range(0, 3);
            for (uint32_t k = 0; k < writes; ++k) {
                std::vector<uint32_t> writable;
                const bool reuse = chance(o.mistakes);
                for (uint32_t r = 0; r < resourceCount; ++r) {
                    if (std::find(touched.begin(), touched.end(), r) != touched.end() && !reuse)
                        continue;
                    if (canWrite(g.resources[r], p.type, sizeClass, m_sizeClass[r], p.accesses, g))
                        writable.push_back(r);
                }
                if (writable.empty()) break;
                const uint32_t r = pick(writable);
                Access a;
                a.resource = g.resources[r].name;
                a.usage = writeUsage(g.resources[r], p.type);
                // Written earlier in this very pass is a deliberate feedback mistake: nothing to order.
                const bool written =
                    lastWriter[r] >= 0 && lastWriter[r] != static_cast<int32_t>(pi);
                if (written && !g.resources[r].imported && !chance(o.mistakes)) {
                    // Order behind the previous writer: read what is there, or say `after`.
                    const bool canLoad = a.usage == Usage::ColorAttachment ||
                                         a.usage == Usage::DepthStencilAttachment ||
                                         a.usage == Usage::StorageWrite;
                    if (canLoad && chance(0.5)) {
                        if (a.usage == Usage::StorageWrite)
                            a.usage = Usage::StorageReadWrite;
                        else
                            a.load = true;
                    } else {
                        p.after.push_back(g.passes[static_cast<size_t>(lastWriter[r])].name);
                    }
                }
                p.accesses.push_back(a);
                touched.push_back(r);
                if (p.enabled) lastWriter[r] = static_cast<int32_t>(pi);
            }

            if (pi > 0 && chance(0.1)) p.after.push_back(g.passes[range(0, pi - 1)].name);
            // A forward `after` moves this pass behind a later one, or closes a cycle.
            if (pi + 1 < passCount && chance(o.forwardAfter))
                p.after.push_back("p" + std::to_string(range(pi + 1, passCount - 1)));
            g.passes.push_back(std::move(p));
        }
        return g;
    }

private:
    uint32_t range(uint32_t lo, uint32_t hi) {
        return std::uniform_int_distribution<uint32_t>(lo, hi)(m_rng);
    }
    double unit() { return std::uniform_real_distribution<double>(0.0, 1.0)(m_rng); }
    bool chance(double p) { return unit() < p; }
    uint32_t pick(const std::vector<uint32_t>& v) {
        return v[range(0, static_cast<uint32_t>(v.size()) - 1)];
    }

    ResourceDesc makeResource(uint32_t i) {
        static constexpr Format kColour[] = {
            Format::R8Unorm,    Format::RGBA8Unorm, Format::RGBA8Srgb, Format::RGB10A2Unorm,
            Format::R11G11B10F, Format::RGBA16F,    Format::R32F,      Format::RG16F,
            Format::R32Uint,    Format::RGBA32F};
        static constexpr Format kDepth[] = {Format::D32F, Format::D24S8, Format::D32FS8,
                                            Format::D16};
        ResourceDesc r;
        r.name = "r" + std::to_string(i);
        r.imported = chance(0.1);
        r.exported = chance(0.15);
        if (chance(0.2)) {
            r.kind = ResourceKind::Buffer;
            r.buffer.size = 1 + range(0, 1u << 20);
            m_sizeClass.push_back(-1);
            return r;
        }
        r.texture.format = chance(0.15) ? kDepth[range(0, 3)] : kColour[range(0, 9)];
        const uint32_t sizeClass = range(0, 3);
        switch (sizeClass) {
            case 0:
                break;  // output size
            case 1:
                r.texture.scaleX = r.texture.scaleY = 0.5f;
                break;
            case 2:
                r.texture.sizeMode = SizeMode::Absolute;
                r.texture.width = r.texture.height = 256;
                break;
            default:
                r.texture.sizeMode = SizeMode::Absolute;
                r.texture.width = 64;
                r.texture.height = 32;
                break;
        }
        r.texture.mips = chance(0.2) ? 0u : chance(0.1) ? 3u : 1u;
        m_sizeClass.push_back(static_cast<int32_t>(sizeClass));
        return r;
    }

    Usage readUsage(const ResourceDesc& r, PassType type) {
        if (type == PassType::Transfer) return Usage::CopySrc;
        if (r.kind == ResourceKind::Buffer)
            return chance(0.5) ? Usage::UniformRead : Usage::StorageRead;
        const FormatInfo& f = formatInfo(r.texture.format);
        if (isDepthStencil(r.texture.format))
            return type == PassType::Raster && chance(0.3) ? Usage::DepthStencilRead
                                                           : Usage::Sampled;
        if (!f.srgb && chance(0.3)) return Usage::StorageRead;
        return Usage::Sampled;
    }

    bool canWrite(const ResourceDesc& r, PassType type, uint32_t passSizeClass, int32_t sizeClass,
                  const std::vector<Access>& accesses, const GraphDesc& g) {
        if (type == PassType::Transfer) return true;
        const bool depth = r.kind == ResourceKind::Texture && isDepthStencil(r.texture.format);
        if (type == PassType::Compute)
            return r.kind == ResourceKind::Buffer || (!depth && !formatInfo(r.texture.format).srgb);
        if (r.kind == ResourceKind::Buffer || sizeClass != static_cast<int32_t>(passSizeClass))
            return false;
        // Raster: attachments of one size; one depth attachment; reads as DepthStencilRead share the size too.
        for (const Access& a : accesses) {
            const ResourceDesc* other = g.findResource(a.resource);
            if (a.usage == Usage::DepthStencilRead || a.usage == Usage::DepthStencilAttachment) {
                if (depth) return false;
                if (other &&
                    m_sizeClass[static_cast<size_t>(other - g.resources.data())] != sizeClass)
                    return false;
            }
        }
        return true;
    }

    Usage writeUsage(const ResourceDesc& r, PassType type) {
        if (type == PassType::Transfer) return Usage::CopyDst;
        if (type == PassType::Compute) return Usage::StorageWrite;
        return isDepthStencil(r.texture.format) ? Usage::DepthStencilAttachment
                                                : Usage::ColorAttachment;
    }

    std::mt19937 m_rng;
    std::vector<int32_t> m_sizeClass;  // per resource; -1 for buffers
};

// The dependency edges graph.h defines, recomputed from the declarations: u must run before v.
std::vector<std::pair<uint32_t, uint32_t>> dependencyEdges(const GraphDesc& g) {
    std::vector<std::pair<uint32_t, uint32_t>> edges;
    std::vector<int32_t> lastWriter(g.resources.size(), -1);
    std::vector<std::vector<uint32_t>> readers(g.resources.size());
    auto resourceIndex = [&](const std::string& name) {
        return static_cast<size_t>(g.findResource(name) - g.resources.data());
    };
    for (uint32_t pi = 0; pi < g.passes.size(); ++pi) {
        const PassDesc& p = g.passes[pi];
        if (!p.enabled) continue;
        for (const std::string& a : p.after) {
            const auto q = static_cast<uint32_t>(g.findPass(a) - g.passes.data());
            if (g.passes[q].enabled) edges.emplace_back(q, pi);
        }
        for (const Access& a : p.accesses) {
            if (!usageReads(a.usage, a.load)) continue;
            const size_t r = resourceIndex(a.resource);
            if (lastWriter[r] >= 0) edges.emplace_back(static_cast<uint32_t>(lastWriter[r]), pi);
            readers[r].push_back(pi);
        }
        for (const Access& a : p.accesses) {
            if (!usageWrites(a.usage)) continue;
            const size_t r = resourceIndex(a.resource);
            if (lastWriter[r] >= 0) edges.emplace_back(static_cast<uint32_t>(lastWriter[r]), pi);
            for (uint32_t q : readers[r])
                if (q != pi) edges.emplace_back(q, pi);
            readers[r].clear();
            lastWriter[r] = static_cast<int32_t>(pi);
        }
    }
    return edges;
}

bool lifetimesIntersect(const PlanResource& a, const PlanResource& b) {
    return a.firstPass <= b.lastPass && b.firstPass <= a.lastPass;
}

bool memoryOverlaps(const PlanResource& a, const PlanResource& b) {
    return a.offset < b.offset + b.memory.size && b.offset < a.offset + a.memory.size;
}

// (a) transients that live at the same time never share bytes; placements fit their heap.
void checkPlacement(const Plan& plan) {
    for (size_t i = 0; i < plan.resources.size(); ++i) {
        const PlanResource& a = plan.resources[i];
        if (!a.transient) {
            ASSERT_EQ(a.heap, -1) << a.name;
            continue;
        }
        ASSERT_GE(a.heap, 0) << a.name;
        ASSERT_LT(static_cast<size_t>(a.heap), plan.heaps.size());
        EXPECT_EQ(a.offset % a.memory.alignment, 0u) << a.name;
        EXPECT_LE(a.offset + a.memory.size, plan.heaps[static_cast<size_t>(a.heap)].size) << a.name;
        for (size_t j = i + 1; j < plan.resources.size(); ++j) {
            const PlanResource& b = plan.resources[j];
            if (!b.transient || b.heap != a.heap || !lifetimesIntersect(a, b)) continue;
            EXPECT_FALSE(memoryOverlaps(a, b))
                << a.name << " [" << a.firstPass << "," << a.lastPass << "] @" << a.offset
                << " and " << b.name << " [" << b.firstPass << "," << b.lastPass << "] @"
                << b.offset;
        }
    }
    uint64_t heaps = 0;
    for (const TransientHeap& h : plan.heaps) heaps += h.size;
    EXPECT_EQ(heaps, plan.transientBytesAliased);
    EXPECT_LE(plan.transientBytesAliased, plan.transientBytesUnaliased);
}

// (b) every read of a kept pass sees something: an import or an earlier scheduled write.
void checkReads(const Plan& plan) {
    std::vector<bool> written(plan.resources.size(), false);
    for (const PlanPass& p : plan.passes) {
        for (const PlanAccess& a : p.accesses)
            if (usageReads(a.usage, a.load)) {
                EXPECT_TRUE(plan.resources[a.resource].imported || written[a.resource])
                    << "pass '" << p.name << "' reads '" << plan.resources[a.resource].name
                    << "' unwritten";
            }
        for (const PlanAccess& a : p.accesses)
            if (usageWrites(a.usage)) written[a.resource] = true;
    }
}

// (c) simulate layouts and writes: a layout change, an access after a write, or a write after any
// access must have a barrier for that resource in that pass, with the right layouts.
void checkBarriers(const Plan& plan) {
    struct Sim {
        Layout layout = Layout::Undefined;
        bool lastWasWrite = false;
        bool touched = false;
    };
    std::vector<Sim> sim(plan.resources.size());
    for (size_t r = 0; r < plan.resources.size(); ++r) {
        if (!plan.resources[r].imported) continue;
        sim[r].layout = plan.resources[r].kind == ResourceKind::Texture ? Layout::ShaderReadOnly
                                                                        : Layout::Undefined;
        sim[r].lastWasWrite = true;
        sim[r].touched = true;
    }
    for (const PlanPass& p : plan.passes) {
        std::vector<uint32_t> seen;
        for (const PlanAccess& a : p.accesses) {
            if (std::find(seen.begin(), seen.end(), a.resource) != seen.end()) continue;
            seen.push_back(a.resource);
            bool writes = false;
            for (const PlanAccess& b : p.accesses)
                if (b.resource == a.resource) writes = writes || usageWrites(b.usage);
            const PlanResource& r = plan.resources[a.resource];
            const bool texture = r.kind == ResourceKind::Texture;
            Sim& s = sim[a.resource];
            const bool needed =
                (texture && a.layout != s.layout) || s.lastWasWrite || (writes && s.touched);
            const Barrier* found = nullptr;
            for (const Barrier& b : p.barriers)
                if (b.resource == a.resource) found = &b;
            if (needed) {
                EXPECT_TRUE(found)
                    << "pass '" << p.name << "' has no barrier for '" << r.name << "'";
            }
            if (found && texture) {
                EXPECT_EQ(found->oldLayout, s.layout) << p.name << " " << r.name;
                EXPECT_EQ(found->newLayout, a.layout) << p.name << " " << r.name;
                EXPECT_NE(found->dstStages, 0u);
            }
            if (found && found->aliasedFrom >= 0) {
                const PlanResource& old = plan.resources[static_cast<size_t>(found->aliasedFrom)];
                EXPECT_EQ(old.heap, r.heap);
                EXPECT_LT(old.lastPass, r.firstPass);
                EXPECT_TRUE(memoryOverlaps(old, r));
            }
            if (texture) s.layout = a.layout;
            s.lastWasWrite = writes;
            s.touched = true;
        }
    }
    // Imported and persistent textures are put back into ShaderReadOnly after the last pass.
    for (const Barrier& b : plan.finalBarriers) {
        const PlanResource& r = plan.resources[b.resource];
        EXPECT_TRUE(r.imported || r.persistent);
        EXPECT_EQ(b.oldLayout, sim[b.resource].layout);
        EXPECT_EQ(b.newLayout, Layout::ShaderReadOnly);
        sim[b.resource].layout = b.newLayout;
    }
    for (size_t r = 0; r < plan.resources.size(); ++r)
        if (plan.resources[r].kind == ResourceKind::Texture) {
            EXPECT_EQ(plan.resources[r].finalLayout, sim[r].layout);
            if (plan.resources[r].imported || plan.resources[r].persistent) {
                EXPECT_EQ(plan.resources[r].finalLayout, Layout::ShaderReadOnly);
            }
        }
}

// (d) the schedule respects every edge between kept passes; culled + kept = all; roots are kept.
void checkSchedule(const GraphDesc& g, const Plan& plan) {
    std::vector<int32_t> position(g.passes.size(), -1);
    for (size_t i = 0; i < plan.passes.size(); ++i)
        position[plan.passes[i].desc] = static_cast<int32_t>(i);
    for (auto [u, v] : dependencyEdges(g)) {
        if (position[u] < 0 || position[v] < 0) continue;
        EXPECT_LT(position[u], position[v]) << g.passes[u].name << " -> " << g.passes[v].name;
    }
    EXPECT_EQ(plan.passes.size() + plan.culled.size(), g.passes.size());
    for (size_t pi = 0; pi < g.passes.size(); ++pi) {
        const PassDesc& p = g.passes[pi];
        if (!p.enabled) {
            EXPECT_EQ(position[pi], -1);
            continue;
        }
        bool root = p.sideEffect;
        for (const Access& a : p.accesses) {
            const ResourceDesc* r = g.findResource(a.resource);
            root = root || (usageWrites(a.usage) && (r->exported || r->imported));
        }
        if (root) {
            EXPECT_GE(position[pi], 0) << p.name;
        }
    }
}

TEST(CompilerProperty, RandomGraphsKeepTheInvariants) {
    GraphGenerator gen(20240601u);
    int compiled = 0, rejected = 0, reordered = 0;
    for (int i = 0; i < 3000; ++i) {
        const GraphDesc g = gen.generate({});
        auto plan = compile(g, CompileOptions{});
        if (!plan) {
            // Invalid input is a value, and names a pass or resource.
            EXPECT_FALSE(plan.error().message.empty());
            if (std::getenv("RG_PRINT_REJECTED")) std::printf("%s\n", plan.error().message.c_str());
            ++rejected;
            continue;
        }
        ++compiled;
        for (size_t k = 1; k < plan->passes.size(); ++k)
            if (plan->passes[k].desc < plan->passes[k - 1].desc) {
                ++reordered;
                break;
            }
        SCOPED_TRACE("graph " + std::to_string(i));
        checkPlacement(*plan);
        checkReads(*plan);
        checkBarriers(*plan);
        checkSchedule(g, *plan);
        if (::testing::Test::HasFailure()) break;  // one broken graph is enough to read
    }
    std::printf(
        "random graphs: %d compiled (%d scheduled out of declaration order), %d rejected as "
        "invalid\n",
        compiled, reordered, rejected);
    // Most graphs must compile, or the properties above prove little.
    EXPECT_GT(compiled, 2000);
    EXPECT_GT(rejected, 50);   // and the rejection paths are exercised too
    EXPECT_GT(reordered, 30);  // and `after` really moves passes
}

TEST(CompilerProperty, AliasOffNeverSharesMemory) {
    GraphGenerator gen(7u);
    for (int i = 0; i < 300; ++i) {
        const GraphDesc g = gen.generate({.mistakes = 0.0, .forwardAfter = 0.0});
        CompileOptions o;
        o.alias = false;
        auto plan = compile(g, o);
        ASSERT_TRUE(plan) << plan.error().message;
        EXPECT_EQ(plan->transientBytesAliased, plan->transientBytesUnaliased);
        for (size_t a = 0; a < plan->resources.size(); ++a)
            for (size_t b = a + 1; b < plan->resources.size(); ++b) {
                const PlanResource& x = plan->resources[a];
                const PlanResource& y = plan->resources[b];
                if (x.transient && y.transient && x.heap == y.heap) {
                    EXPECT_FALSE(memoryOverlaps(x, y));
                }
            }
    }
}

TEST(CompilerProperty, Figures200Passes) {
    GraphGenerator gen(200u);
    const GraphDesc g =
        gen.generate({.minPasses = 200, .maxPasses = 200, .mistakes = 0.0, .forwardAfter = 0.0});
    auto plan = compile(g, CompileOptions{});
    ASSERT_TRUE(plan) << plan.error().message;
    checkPlacement(*plan);
    checkBarriers(*plan);
    checkSchedule(g, *plan);

    // Best of a few runs: the figure is the compiler's cost, not the machine's noise.
    double best = 1e30;
    std::vector<StepTiming> bestSteps;
    for (int run = 0; run < 5; ++run) {
        const auto start = std::chrono::steady_clock::now();
        auto again = compile(g, CompileOptions{});
        const std::chrono::duration<double, std::milli> ms =
            std::chrono::steady_clock::now() - start;
        ASSERT_TRUE(again);
        if (ms.count() < best) {
            best = ms.count();
            bestSteps = again->timings;
        }
    }
    size_t transients = 0, barriers = 0;
    for (const auto& r : plan->resources) transients += r.transient ? 1 : 0;
    for (const auto& p : plan->passes) barriers += p.barriers.size();
    std::printf(
        "200-pass graph: %zu resources declared, %zu kept passes, %zu culled, %zu transients in "
        "%zu heaps, "
        "%zu barriers\n",
        g.resources.size(), plan->passes.size(), plan->culled.size(), transients,
        plan->heaps.size(), barriers);
    std::printf(
        "200-pass graph: compile %.3f ms (best of 5); transient memory aliased %.2f MiB vs "
        "unaliased "
        "%.2f MiB (%.1f%%)\n",
        best, static_cast<double>(plan->transientBytesAliased) / 1048576.0,
        static_cast<double>(plan->transientBytesUnaliased) / 1048576.0,
        plan->transientBytesUnaliased ? 100.0 * static_cast<double>(plan->transientBytesAliased) /
                                            static_cast<double>(plan->transientBytesUnaliased)
                                      : 100.0);
    for (const auto& t : bestSteps) std::printf("  %-9s %.3f ms\n", t.step.c_str(), t.ms);
    EXPECT_LE(plan->transientBytesAliased, plan->transientBytesUnaliased);
}

}  // namespace

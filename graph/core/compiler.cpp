// compile(): validate -> cull -> schedule -> lifetimes -> alias -> barriers (Granite's bake()
// as named steps; Filament's reference-count culling). See graph.h for the ordering model.
#include "compiler.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <queue>
#include <type_traits>
#include <unordered_map>

#include "check.h"
#include "names.h"

namespace rg {

namespace {

constexpr uint32_t kWriteAccessBits = access::ShaderStorageWrite | access::ColorAttachmentWrite |
                                      access::DepthStencilWrite | access::TransferWrite |
                                      access::HostWrite | access::MemoryWrite;
// Texture dimensions beyond this are a typo in a script, not a render target.
constexpr uint32_t kMaxDimension = 65536;
constexpr uint64_t kTextureAlignment = 64 * 1024;
constexpr uint64_t kBufferAlignment = 256;  // common minStorageBufferOffsetAlignment upper bound

uint64_t alignUp(uint64_t v, uint64_t a) { return a <= 1 ? v : (v + a - 1) / a * a; }

struct Extent {
    uint32_t width = 0;
    uint32_t height = 0;
};

// OutputRelative: max(1, floor(output * scale)); Absolute: as declared.
uint32_t scaledDimension(uint32_t output, float scale) {
    const double v = std::floor(static_cast<double>(output) * static_cast<double>(scale));
    if (!(v >= 1.0)) return 1;
    if (v > static_cast<double>(kMaxDimension) * 4.0) return kMaxDimension * 4;
    return static_cast<uint32_t>(v);
}

Extent resolveExtent(const TextureDesc& t, const CompileOptions& o) {
    if (t.sizeMode == SizeMode::Absolute) return {t.width, t.height};
    return {scaledDimension(o.outputWidth, t.scaleX), scaledDimension(o.outputHeight, t.scaleY)};
}

uint64_t resolvedBufferSize(const BufferDesc& b, const CompileOptions& o) {
    if (b.tileSize == 0) return b.size;
    const uint64_t tx = (o.outputWidth + b.tileSize - 1) / b.tileSize, ty = (o.outputHeight + b.tileSize - 1) / b.tileSize;
    return b.size + tx * ty * b.tileBytes;
}

// floor(log2(max(w, h))) + 1
uint32_t fullMipChain(Extent e) {
    uint32_t m = std::max(e.width, e.height);
    uint32_t n = 0;
    for (; m != 0; m >>= 1) ++n;
    return std::max(n, 1u);
}

uint32_t resolvedLayers(const TextureDesc& t) { return t.cube && t.layers <= 1 ? 6u : t.layers; }

std::string extentText(Extent e) { return std::to_string(e.width) + "x" + std::to_string(e.height); }

bool isAttachment(Usage u) {
    return u == Usage::ColorAttachment || u == Usage::DepthStencilAttachment || u == Usage::DepthStencilRead;
}

bool isStorage(Usage u) {
    return u == Usage::StorageRead || u == Usage::StorageWrite || u == Usage::StorageReadWrite;
}

// Lua truthiness: everything but nil and false.
bool truthy(const Value& v) { return !v.isNil() && !(v.isBool() && !v.asBool()); }


// " (did you mean 'x'?)" for the closest name within edit distance 2, earliest declared on ties.
template <class Range, class NameOf>
std::string suggestionAmong(const std::string& wanted, const Range& candidates, NameOf nameOf) {
    std::vector<std::string> names;
    for (const auto& c : candidates) names.push_back(nameOf(c));
    const std::string best = closestName(wanted, names, 3);
    return best.empty() ? std::string() : " (did you mean '" + best + "'?)";
}

std::string withOrigin(const std::string& origin, std::string text) {
    return origin.empty() ? text : origin + ": " + text;
}

std::string quotedList(const std::vector<std::string>& names) {
    std::string s;
    for (size_t i = 0; i < names.size(); ++i) {
        if (i > 0) s += i + 1 == names.size() ? " and " : ", ";
        s += "'" + names[i] + "'";
    }
    return s;
}

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
    std::vector<std::vector<uint32_t>> needs;           // v -> u where v needs u's work (RAW, WAW, after)
    std::vector<bool> kept;
    std::vector<uint32_t> order;                   // scheduled pass desc indices
    std::vector<int32_t> planResource;             // resource desc index -> Plan::resources index
    std::vector<std::vector<uint32_t>> aliasPreds;  // plan resource -> earlier occupants of its memory
    std::vector<int32_t> aliasFrom;                // plan resource -> most recent earlier occupant

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

Status invalid(std::string text) { return fail(ErrorCode::InvalidInput, std::move(text)); }

// validate (1/4): names, sizes and formats of the resources.
Status validateResources(Compiler& c) {
    const auto& resources = c.graph.resources;
    for (size_t i = 0; i < resources.size(); ++i) {
        const ResourceDesc& r = resources[i];
        const std::string at = "resources[" + std::to_string(i) + "]";
        if (r.name.empty()) return invalid(withOrigin(r.origin, at + " has no name"));
        if (auto [it, fresh] = c.resourceIndex.emplace(r.name, static_cast<uint32_t>(i)); !fresh)
            return invalid(withOrigin(r.origin, "resource '" + r.name + "' is declared twice (resources[" +
                                                    std::to_string(it->second) + "] and " + at + ")"));
        const std::string what = "resource '" + r.name + "': ";
        if (r.kind == ResourceKind::Buffer) {
            if (r.buffer.size == 0)
                return invalid(withOrigin(r.origin, what + "buffer size is 0 bytes; it must be at least 1"));
            continue;
        }
        const TextureDesc& t = r.texture;
        if (t.format == Format::Undefined || t.format >= Format::Count)
            return invalid(withOrigin(r.origin, what + "texture has no format (expected one of: " +
                                                    formatNameList() + ")"));
        if (t.sizeMode == SizeMode::Absolute) {
            if (t.width == 0 || t.height == 0)
                return invalid(withOrigin(r.origin, what + "absolute size " + std::to_string(t.width) + "x" +
                                                        std::to_string(t.height) +
                                                        "; width and height must be at least 1"));
        } else if (!(t.scaleX > 0.0f) || !(t.scaleY > 0.0f) || !std::isfinite(t.scaleX) ||
                   !std::isfinite(t.scaleY)) {
            return invalid(withOrigin(r.origin, what + "output-relative scale " + std::to_string(t.scaleX) +
                                                    " x " + std::to_string(t.scaleY) + " must be positive"));
        }
        const Extent e = resolveExtent(t, c.options);
        if (e.width > kMaxDimension || e.height > kMaxDimension)
            return invalid(withOrigin(r.origin, what + "size " + extentText(e) + " exceeds " +
                                                    std::to_string(kMaxDimension) + " texels"));
        if (t.layers == 0) return invalid(withOrigin(r.origin, what + "layers is 0; it must be at least 1"));
        if (t.cube) {
            if (e.width != e.height)
                return invalid(withOrigin(r.origin, what + "a cube texture must be square, got " + extentText(e)));
            if (t.layers != 1 && t.layers % 6 != 0)
                return invalid(withOrigin(r.origin, what + "a cube texture has 6 layers per cube, got " +
                                                        std::to_string(t.layers)));
        }
        if (t.mips > fullMipChain(e))
            return invalid(withOrigin(r.origin, what + std::to_string(t.mips) + " mips requested, but a " +
                                                    extentText(e) + " texture has at most " +
                                                    std::to_string(fullMipChain(e))));
    }
    return {};
}

// The reason a usage cannot apply to a resource (kind, format, pass type); empty when it can.
std::string usageConflict(const PassDesc& pass, const Access& a, const ResourceDesc& r) {
    const std::string use = usageName(a.usage);
    if (isAttachment(a.usage) && pass.type == PassType::Compute)
        return use + " needs a raster pass, but '" + pass.name + "' is a compute pass";
    if (r.kind == ResourceKind::Buffer) {
        if (a.usage == Usage::IndirectRead && pass.type != PassType::Raster)
            return use + " needs a raster pass (indirect draws), but '" + pass.name + "' is a " + passTypeName(pass.type) + " pass";
        if (a.usage == Usage::UniformRead || isStorage(a.usage) || a.usage == Usage::CopySrc ||
            a.usage == Usage::CopyDst || a.usage == Usage::IndirectRead)
            return {};
        return "'" + r.name + "' is a buffer, which cannot be used as " + use +
               " (expected UniformRead, StorageRead, StorageWrite, StorageReadWrite, IndirectRead, CopySrc or CopyDst)";
    }
    if (a.usage == Usage::IndirectRead)
        return "'" + r.name + "' is a texture, which cannot be used as IndirectRead (indirect commands live in buffers)";
    if (a.usage == Usage::UniformRead)
        return "'" + r.name + "' is a texture, which cannot be used as UniformRead (uniform reads are for buffers)";
    const FormatInfo& f = formatInfo(r.texture.format);
    const std::string fmt = "'" + std::string(f.name) + "'";
    if (isDepthStencil(r.texture.format)) {
        if (a.usage == Usage::DepthStencilAttachment || a.usage == Usage::DepthStencilRead ||
            a.usage == Usage::Sampled || a.usage == Usage::CopySrc || a.usage == Usage::CopyDst)
            return {};
        return "'" + r.name + "' has depth format " + fmt + ", which cannot be used as " + use +
               " (expected DepthStencilAttachment, DepthStencilRead, Sampled, CopySrc or CopyDst)";
    }
    if (a.usage == Usage::DepthStencilAttachment || a.usage == Usage::DepthStencilRead)
        return "'" + r.name + "' has colour format " + fmt + ", which cannot be used as " + use +
               " (needs a depth format: d16, d32f, d24_s8 or d32f_s8)";
    if (f.srgb && isStorage(a.usage))
        return "'" + r.name + "' has sRGB format " + fmt + ", which cannot be used as " + use +
               " (sRGB formats cannot be storage images; use a UNORM format and encode in the shader)";
    if (f.integer && a.usage == Usage::ColorAttachment && truthy(pass.params["blend"]))
        return "'" + r.name + "' has integer format " + fmt +
               ", which cannot be a blended ColorAttachment (params.blend is set)";
    return {};
}

// Layout a texture usage needs in a pass of this type (buffers: Undefined).
Layout usageLayout(Usage u, PassType type) {
    if (type == PassType::Transfer) return usageWrites(u) ? Layout::TransferDst : Layout::TransferSrc;
    switch (u) {
    case Usage::Sampled: return Layout::ShaderReadOnly;
    case Usage::UniformRead:
    case Usage::IndirectRead: return Layout::Undefined;
    case Usage::StorageRead:
    case Usage::StorageWrite:
    case Usage::StorageReadWrite: return Layout::General;
    case Usage::ColorAttachment: return Layout::ColorAttachment;
    case Usage::DepthStencilAttachment: return Layout::DepthStencilAttachment;
    case Usage::DepthStencilRead: return Layout::DepthStencilReadOnly;
    case Usage::CopySrc: return Layout::TransferSrc;
    case Usage::CopyDst: return Layout::TransferDst;
    }
    return Layout::Undefined;
}

// validate (2/4): pass names, accesses against the resources, feedback, attachment sizes, `after`.
Status validatePasses(Compiler& c) {
    const auto& passes = c.graph.passes;
    const auto& resources = c.graph.resources;
    c.accessResource.assign(passes.size(), {});
    c.merged.assign(passes.size(), {});
    for (size_t i = 0; i < passes.size(); ++i) {
        const PassDesc& p = passes[i];
        const std::string at = "passes[" + std::to_string(i) + "]";
        if (p.name.empty()) return invalid(withOrigin(p.origin, at + " has no name"));
        if (auto [it, fresh] = c.passIndex.emplace(p.name, static_cast<uint32_t>(i)); !fresh)
            return invalid(withOrigin(p.origin, "pass '" + p.name + "' is declared twice (passes[" +
                                                    std::to_string(it->second) + "] and " + at + ")"));
    }

    for (uint32_t pi = 0; pi < passes.size(); ++pi) {
        const PassDesc& p = passes[pi];
        auto& resolved = c.accessResource[pi];
        for (uint32_t ai = 0; ai < p.accesses.size(); ++ai) {
            const Access& a = p.accesses[ai];
            // Built only on the error path: validation runs on every recompile.
            auto where = [&] { return "pass '" + p.name + "' field '" + c.fieldOf(pi, ai) + "': "; };
            const auto found = c.resourceIndex.find(a.resource);
            const ResourceDesc* r = found == c.resourceIndex.end() ? nullptr : &resources[found->second];
            if (!r)
                return invalid(c.passError(pi, where() + "unknown resource '" + a.resource + "'" +
                                                   suggestionAmong(a.resource, resources,
                                                              [](const ResourceDesc& d) -> const std::string& {
                                                                  return d.name;
                                                              })));
            const auto ri = static_cast<uint32_t>(r - resources.data());
            if (std::string why = usageConflict(p, a, *r); !why.empty())
                return invalid(c.passError(pi, where() + why));
            // A pass may bind one resource twice only to read it the same way.
            for (uint32_t bi = 0; bi < ai; ++bi) {
                if (resolved[bi] != ri) continue;
                const Access& b = p.accesses[bi];
                const std::string other =
                    std::string(usageName(b.usage)) + " (field '" + c.fieldOf(pi, bi) + "')";
                if (usageWrites(a.usage) && b.usage == a.usage)
                    return invalid(c.passError(pi, where() + "'" + r->name + "' is already written as " + other +
                                                       " in this pass"));
                if (usageWrites(a.usage) || usageWrites(b.usage))
                    return invalid(c.passError(pi, where() + "'" + r->name + "' is used as " + usageName(a.usage) +
                                                       " and also as " + other + " in the same pass (feedback loop)"));
                // Sampling a depth buffer that is also the read-only depth/stencil attachment is
                // fine: both read, in DepthStencilReadOnly (deferred lighting tests stencil and
                // reads depth for positions).
                const bool depthReadAndSample =
                    (a.usage == Usage::Sampled && b.usage == Usage::DepthStencilRead) ||
                    (a.usage == Usage::DepthStencilRead && b.usage == Usage::Sampled);
                if (r->kind == ResourceKind::Texture && !depthReadAndSample &&
                    usageLayout(a.usage, p.type) != usageLayout(b.usage, p.type))
                    return invalid(c.passError(pi, where() + "'" + r->name + "' is used as " + usageName(a.usage) +
                                                       " and also as " + other +
                                                       " in the same pass, which need different layouts"));
            }
            resolved.push_back(ri);
            auto m = std::find_if(c.merged[pi].begin(), c.merged[pi].end(),
                                  [&](const MergedAccess& x) { return x.resource == ri; });
            if (m == c.merged[pi].end()) m = c.merged[pi].insert(c.merged[pi].end(), MergedAccess{ri});
            m->reads = m->reads || usageReads(a.usage, a.load);
            m->writes = m->writes || usageWrites(a.usage);
        }

        // Dynamic rendering needs one render area for all attachments of a raster pass.
        if (p.type == PassType::Raster) {
            int32_t depthAt = -1;
            for (uint32_t ai = 0; ai < p.accesses.size(); ++ai) {
                const Usage u = p.accesses[ai].usage;
                if (u != Usage::DepthStencilAttachment && u != Usage::DepthStencilRead) continue;
                if (depthAt >= 0 && resolved[static_cast<uint32_t>(depthAt)] != resolved[ai])
                    return invalid(c.passError(
                        pi, "pass '" + p.name + "' field '" + c.fieldOf(pi, ai) + "': '" + p.accesses[ai].resource +
                                "' would be a second depth/stencil attachment (the pass already has '" +
                                p.accesses[static_cast<uint32_t>(depthAt)].resource + "')"));
                if (depthAt < 0) depthAt = static_cast<int32_t>(ai);
            }
            int32_t first = -1;
            for (uint32_t ai = 0; ai < p.accesses.size(); ++ai) {
                if (!isAttachment(p.accesses[ai].usage)) continue;
                if (first < 0) {
                    first = static_cast<int32_t>(ai);
                    continue;
                }
                const ResourceDesc& ra = resources[resolved[static_cast<uint32_t>(first)]];
                const ResourceDesc& rb = resources[resolved[ai]];
                const Extent ea = resolveExtent(ra.texture, c.options);
                const Extent eb = resolveExtent(rb.texture, c.options);
                if (ea.width != eb.width || ea.height != eb.height)
                    return invalid(c.passError(pi, "pass '" + p.name + "': attachments differ in size: '" +
                                                       ra.name + "' is " + extentText(ea) + " but '" + rb.name +
                                                       "' is " + extentText(eb)));
            }
        }

        for (size_t k = 0; k < p.after.size(); ++k) {
            if (c.passIndex.contains(p.after[k])) continue;
            return invalid(c.passError(
                pi, "pass '" + p.name + "' field 'after[" + std::to_string(k) + "]': unknown pass '" + p.after[k] +
                        "'" + suggestionAmong(p.after[k], passes, [](const PassDesc& d) -> const std::string& {
                            return d.name;
                        })));
        }
    }
    return {};
}

// validate (3/4): walk the versions in declaration order and derive RAW / WAR / WAW / after edges.
Status validateVersions(Compiler& c) {
    const auto& passes = c.graph.passes;
    const auto& resources = c.graph.resources;
    const auto passCount = static_cast<uint32_t>(passes.size());
    c.successors.assign(passCount, {});
    c.needs.assign(passCount, {});
    std::vector<int32_t> lastWriter(resources.size(), -1);
    std::vector<int32_t> disabledWriter(resources.size(), -1);
    std::vector<std::vector<uint32_t>> readers(resources.size());


    for (uint32_t pi = 0; pi < passCount; ++pi) {
        const PassDesc& p = passes[pi];
        if (!p.enabled) {
            for (const MergedAccess& m : c.merged[pi])
                if (m.writes) disabledWriter[m.resource] = static_cast<int32_t>(pi);
            continue;
        }
        for (const std::string& name : p.after) {
            const uint32_t q = c.passIndex.at(name);
            if (passes[q].enabled) c.addEdge(q, pi, /* need= */ true);
        }
        for (const MergedAccess& m : c.merged[pi]) {
            if (!m.reads) continue;
            const ResourceDesc& r = resources[m.resource];
            if (lastWriter[m.resource] >= 0) {
                c.addEdge(static_cast<uint32_t>(lastWriter[m.resource]), pi, /* need= */ true);
            } else if (!r.imported && !r.persistent) {
                if (disabledWriter[m.resource] >= 0)
                    return invalid(c.passError(pi, "pass '" + p.name + "' reads '" + r.name + "', but its only writer '" +
                                                       passes[static_cast<size_t>(disabledWriter[m.resource])].name +
                                                       "' is disabled"));
                std::string text = "pass '" + p.name + "' reads '" + r.name + "' before any pass writes it";
                for (uint32_t later = pi + 1; later < passCount; ++later) {
                    if (!passes[later].enabled) continue;
                    const auto& lm = c.merged[later];
                    if (std::any_of(lm.begin(), lm.end(),
                                    [&](const MergedAccess& x) { return x.resource == m.resource && x.writes; })) {
                        text += " (first written by '" + passes[later].name + "', declared later)";
                        break;
                    }
                }
                return invalid(c.passError(pi, text));
            }
            readers[m.resource].push_back(pi);
        }
        for (const MergedAccess& m : c.merged[pi]) {
            if (!m.writes) continue;
            const ResourceDesc& r = resources[m.resource];
            if (const int32_t w = lastWriter[m.resource]; w >= 0) {
                const std::string& writer = passes[static_cast<size_t>(w)].name;
                const bool ordered = std::find(p.after.begin(), p.after.end(), writer) != p.after.end();
                if (!m.reads && !r.imported && !r.persistent && !ordered)
                    return invalid(c.passError(pi, "passes '" + writer + "' and '" + p.name + "' both write '" +
                                                       r.name + "' with no order between them: make '" + p.name +
                                                       "' load it or list '" + writer + "' in its after"));
                c.addEdge(static_cast<uint32_t>(w), pi, /* need= */ true);
            }
            for (uint32_t q : readers[m.resource])
                if (q != pi) c.addEdge(q, pi, /* need= */ false);
            readers[m.resource].clear();
            lastWriter[m.resource] = static_cast<int32_t>(pi);
        }
    }
    for (auto& s : c.successors) {
        std::sort(s.begin(), s.end());
        s.erase(std::unique(s.begin(), s.end()), s.end());
    }
    for (auto& n : c.needs) {
        std::sort(n.begin(), n.end());
        n.erase(std::unique(n.begin(), n.end()), n.end());
    }
    return {};
}

// validate (4/4): a cycle can only come from `after`; report the first one found, from its earliest pass.
Status validateCycles(Compiler& c) {
    const auto n = static_cast<uint32_t>(c.graph.passes.size());
    enum class Mark : uint8_t { White, Grey, Black };
    std::vector<Mark> mark(n, Mark::White);
    std::vector<uint32_t> path;
    struct Frame {
        uint32_t pass;
        size_t next;
    };
    for (uint32_t start = 0; start < n; ++start) {
        if (mark[start] != Mark::White) continue;
        std::vector<Frame> stack{{start, 0}};
        mark[start] = Mark::Grey;
        path.assign(1, start);
        while (!stack.empty()) {
            Frame& f = stack.back();
            const auto& succ = c.successors[f.pass];
            if (f.next == succ.size()) {
                mark[f.pass] = Mark::Black;
                stack.pop_back();
                path.pop_back();
                continue;
            }
            const uint32_t v = succ[f.next++];
            if (mark[v] == Mark::White) {
                mark[v] = Mark::Grey;
                stack.push_back({v, 0});
                path.push_back(v);
            } else if (mark[v] == Mark::Grey) {
                std::vector<uint32_t> cycle(std::find(path.begin(), path.end(), v), path.end());
                std::rotate(cycle.begin(), std::min_element(cycle.begin(), cycle.end()), cycle.end());
                std::string text = "cycle between passes: ";
                for (uint32_t p : cycle) text += "'" + c.graph.passes[p].name + "' -> ";
                text += "'" + c.graph.passes[cycle.front()].name + "'";
                return invalid(c.passError(cycle.front(), text));
            }
        }
    }
    return {};
}

// validate: everything that can be wrong with the declarations, first error in declaration order.
Status validate(Compiler& c) {
    if (auto s = validateResources(c); !s) return s;
    if (auto s = validatePasses(c); !s) return s;
    if (auto s = validateVersions(c); !s) return s;
    return validateCycles(c);
}

// cull: keep side-effect passes and writers of exported/imported resources, and what they need.
void cull(Compiler& c) {
    const auto& passes = c.graph.passes;
    const auto& resources = c.graph.resources;
    c.kept.assign(passes.size(), false);
    std::vector<uint32_t> work;
    for (uint32_t pi = 0; pi < passes.size(); ++pi) {
        if (!passes[pi].enabled) continue;
        bool root = passes[pi].sideEffect;
        for (const MergedAccess& m : c.merged[pi])
            root = root || (m.writes && (resources[m.resource].exported || resources[m.resource].imported ||
                                         resources[m.resource].persistent));
        if (root) {
            c.kept[pi] = true;
            work.push_back(pi);
        }
    }
    // Only RAW, WAW and `after` edges keep a pass: a WAR edge orders a reader before the next
    // writer, but that writer does not need the reader's work.
    while (!work.empty()) {
        const uint32_t p = work.back();
        work.pop_back();
        for (uint32_t q : c.needs[p]) {
            if (c.kept[q]) continue;
            c.kept[q] = true;
            work.push_back(q);
        }
    }
    for (uint32_t pi = 0; pi < passes.size(); ++pi) {
        if (c.kept[pi]) continue;
        const PassDesc& p = passes[pi];
        std::string reason;
        if (!p.enabled) {
            reason = "disabled";
        } else {
            std::vector<std::string> written;
            for (const MergedAccess& m : c.merged[pi])
                if (m.writes) written.push_back(resources[m.resource].name);
            if (written.empty())
                reason = "has no writes and no side effect";
            else
                reason = "writes only " + quotedList(written) + ", which no kept pass reads and " +
                         (written.size() == 1 ? "is" : "are") + " not exported";
        }
        c.plan.culled.push_back({p.name, std::move(reason)});
    }
}

// schedule: stable topological order (Kahn; the ready pass declared first goes first).
void schedule(Compiler& c) {
    const auto n = static_cast<uint32_t>(c.graph.passes.size());
    std::vector<uint32_t> indegree(n, 0);
    for (uint32_t u = 0; u < n; ++u)
        if (c.kept[u])
            for (uint32_t v : c.successors[u])
                if (c.kept[v]) ++indegree[v];
    std::priority_queue<uint32_t, std::vector<uint32_t>, std::greater<>> ready;
    for (uint32_t u = 0; u < n; ++u)
        if (c.kept[u] && indegree[u] == 0) ready.push(u);
    while (!ready.empty()) {
        const uint32_t u = ready.top();
        ready.pop();
        c.order.push_back(u);
        for (uint32_t v : c.successors[u])
            if (c.kept[v] && --indegree[v] == 0) ready.push(v);
    }
    RG_CHECK(c.order.size() == static_cast<size_t>(std::count(c.kept.begin(), c.kept.end(), true)))
        << "schedule: cycle among kept passes survived validation";
    for (uint32_t pi : c.order) {
        const PassDesc& d = c.graph.passes[pi];
        PlanPass p;
        p.desc = pi;
        p.name = d.name;
        p.kind = d.kind;
        p.type = d.type;
        c.plan.passes.push_back(std::move(p));
    }
}

// lifetimes: one PlanResource per resource a kept pass uses; resolved sizes, usages, first/last pass.
void computeLifetimes(Compiler& c) {
    const auto& resources = c.graph.resources;
    std::vector<bool> used(resources.size(), false);
    for (uint32_t pi : c.order)
        for (uint32_t ri : c.accessResource[pi]) used[ri] = true;

    c.planResource.assign(resources.size(), -1);
    for (uint32_t ri = 0; ri < resources.size(); ++ri) {
        if (!used[ri]) continue;
        const ResourceDesc& d = resources[ri];
        PlanResource r;
        r.desc = ri;
        r.name = d.name;
        r.kind = d.kind;
        r.imported = d.imported;
        r.exported = d.exported;
        r.persistent = d.persistent;
        r.transient = !d.imported && !d.exported && !d.persistent;
        if (d.kind == ResourceKind::Buffer) {
            r.bufferSize = resolvedBufferSize(d.buffer, c.options);
        } else {
            const Extent e = resolveExtent(d.texture, c.options);
            r.format = d.texture.format;
            r.width = e.width;
            r.height = e.height;
            r.cube = d.texture.cube;
            r.array = !d.texture.sceneLayers.empty();
            r.layers = resolvedLayers(d.texture);
            r.mips = d.texture.mips == 0 ? fullMipChain(e) : d.texture.mips;
        }
        c.planResource[ri] = static_cast<int32_t>(c.plan.resources.size());
        c.plan.resources.push_back(std::move(r));
    }

    for (uint32_t i = 0; i < c.plan.passes.size(); ++i) {
        PlanPass& p = c.plan.passes[i];
        const PassDesc& d = c.graph.passes[p.desc];
        for (uint32_t ai = 0; ai < d.accesses.size(); ++ai) {
            const auto ri = static_cast<uint32_t>(c.planResource[c.accessResource[p.desc][ai]]);
            PlanResource& r = c.plan.resources[ri];
            r.usageMask |= 1u << static_cast<uint32_t>(d.accesses[ai].usage);
            if (r.firstPass < 0) r.firstPass = static_cast<int32_t>(i);
            r.lastPass = static_cast<int32_t>(i);
            PlanAccess a;
            a.resource = ri;
            a.usage = d.accesses[ai].usage;
            a.load = d.accesses[ai].load;
            p.accesses.push_back(a);
        }
    }
    // Exported contents are read after the frame, so nothing may reuse their memory before its end.
    for (PlanResource& r : c.plan.resources)
        if (r.exported) r.lastPass = static_cast<int32_t>(c.plan.passes.size()) - 1;
}

bool lifetimesIntersect(const PlanResource& a, const PlanResource& b) {
    return a.firstPass <= b.lastPass && b.firstPass <= a.lastPass;
}

bool rangesOverlap(const PlanResource& a, const PlanResource& b) {
    return a.offset < b.offset + b.memory.size && b.offset < a.offset + a.memory.size;
}

// alias: group transients into heaps by memory class and place them, sharing memory across lifetimes.
void alias(Compiler& c) {
    auto& resources = c.plan.resources;
    const MemoryRequirementsFn& query = c.options.memoryRequirements;
    // A reconfiguration keeps the usages a resource had (options.previous): a pass switched off
    // must not make its resources new images of fewer usages, and more usages are harmless.
    if (const Plan* previous = c.options.previous)
        for (PlanResource& r : resources)
            if (const int32_t o = previous->findResource(r.name); o >= 0) {
                const PlanResource& was = previous->resources[static_cast<size_t>(o)];
                if (was.kind == r.kind && was.format == r.format && was.transient == r.transient) r.usageMask |= was.usageMask;
            }
    for (PlanResource& r : resources)
        if (!r.imported) r.memory = query ? query(r) : estimateMemoryRequirements(r);

    std::vector<std::vector<uint32_t>> members;
    for (uint32_t ri = 0; ri < resources.size(); ++ri) {
        PlanResource& r = resources[ri];
        if (!r.transient) continue;
        const bool buffers = r.kind == ResourceKind::Buffer;
        size_t h = 0;
        while (h < c.plan.heaps.size() &&
               (c.plan.heaps[h].memoryTypeBits != r.memory.memoryTypeBits || c.plan.heaps[h].buffers != buffers))
            ++h;
        if (h == c.plan.heaps.size()) {
            c.plan.heaps.push_back({r.memory.memoryTypeBits, buffers, 0});
            members.emplace_back();
        }
        r.heap = static_cast<int32_t>(h);
        members[h].push_back(ri);
        c.plan.transientBytesUnaliased += alignUp(r.memory.size, r.memory.alignment);
    }

    for (size_t h = 0; h < members.size(); ++h) {
        std::vector<uint32_t>& list = members[h];
        uint64_t heapSize = 0;
        // The previous plan's heap of this memory class (options.previous).
        const Plan* previous = c.options.previous;
        const TransientHeap* previousHeap = nullptr;
        if (previous && h < previous->heaps.size() && previous->heaps[h].memoryTypeBits == c.plan.heaps[h].memoryTypeBits &&
            previous->heaps[h].buffers == c.plan.heaps[h].buffers)
            previousHeap = &previous->heaps[h];
        if (c.options.alias) {
            // Largest first packs best; declaration order keeps equal sizes deterministic.
            std::stable_sort(list.begin(), list.end(), [&](uint32_t a, uint32_t b) {
                return resources[a].memory.size > resources[b].memory.size;
            });
            std::vector<uint32_t> placed, toPlace = list;
            // First the transients that can stay where the previous plan had them.
            if (previousHeap) {
                std::vector<uint32_t> rest;
                for (uint32_t ri : list) {
                    PlanResource& r = resources[ri];
                    const int32_t o = previous->findResource(r.name);
                    const PlanResource* was = o >= 0 ? &previous->resources[static_cast<size_t>(o)] : nullptr;
                    bool kept = was && was->transient && was->heap == static_cast<int32_t>(h) && was->memory.size == r.memory.size &&
                                was->memory.alignment == r.memory.alignment && was->offset + r.memory.size <= previousHeap->size;
                    if (kept) {
                        r.offset = was->offset;
                        kept = std::none_of(placed.begin(), placed.end(), [&](uint32_t q) {
                            return lifetimesIntersect(r, resources[q]) && rangesOverlap(r, resources[q]);
                        });
                    }
                    if (!kept) {
                        rest.push_back(ri);
                        continue;
                    }
                    placed.push_back(ri);
                    heapSize = std::max(heapSize, r.offset + alignUp(r.memory.size, r.memory.alignment));
                }
                toPlace = std::move(rest);
            }
            for (uint32_t ri : toPlace) {
                PlanResource& r = resources[ri];
                std::vector<uint64_t> candidates{0};
                std::vector<uint32_t> live;
                for (uint32_t q : placed) {
                    if (!lifetimesIntersect(r, resources[q])) continue;
                    live.push_back(q);
                    candidates.push_back(
                        alignUp(resources[q].offset + resources[q].memory.size, r.memory.alignment));
                }
                std::sort(candidates.begin(), candidates.end());
                for (uint64_t offset : candidates) {
                    r.offset = offset;
                    if (std::none_of(live.begin(), live.end(),
                                     [&](uint32_t q) { return rangesOverlap(r, resources[q]); }))
                        break;
                }
                placed.push_back(ri);
                heapSize = std::max(heapSize, r.offset + alignUp(r.memory.size, r.memory.alignment));
            }
            // A heap the new placement fits in is kept whole (its memory and what lies in it).
            if (previousHeap && heapSize <= previousHeap->size) heapSize = previousHeap->size;
        } else {
            // Largest alignment first, so every aligned size keeps the next offset aligned: no gaps.
            std::stable_sort(list.begin(), list.end(), [&](uint32_t a, uint32_t b) {
                return resources[a].memory.alignment > resources[b].memory.alignment;
            });
            for (uint32_t ri : list) {
                PlanResource& r = resources[ri];
                r.offset = alignUp(heapSize, r.memory.alignment);
                heapSize = r.offset + alignUp(r.memory.size, r.memory.alignment);
            }
        }
        c.plan.heaps[h].size = heapSize;
        c.plan.transientBytesAliased += heapSize;
    }

    // Who used each transient's memory before it: its first barrier must wait for them.
    c.aliasPreds.assign(resources.size(), {});
    c.aliasFrom.assign(resources.size(), -1);
    for (uint32_t ri = 0; ri < resources.size(); ++ri) {
        const PlanResource& r = resources[ri];
        if (!r.transient) continue;
        for (uint32_t q : members[static_cast<size_t>(r.heap)]) {
            const PlanResource& o = resources[q];
            if (q == ri || o.lastPass >= r.firstPass || !rangesOverlap(r, o)) continue;
            c.aliasPreds[ri].push_back(q);
            const int32_t best = c.aliasFrom[ri];
            if (best < 0 || o.lastPass > resources[static_cast<size_t>(best)].lastPass ||
                (o.lastPass == resources[static_cast<size_t>(best)].lastPass && q < static_cast<uint32_t>(best)))
                c.aliasFrom[ri] = static_cast<int32_t>(q);
        }
    }
}

// Stages, access bits and layout an access needs, from its usage and the pass type.
void describeAccess(PlanAccess& a, PassType type, ResourceKind kind) {
    const uint32_t shaderStages =
        type == PassType::Compute ? stage::ComputeShader : stage::VertexShader | stage::FragmentShader;
    const bool texture = kind == ResourceKind::Texture;
    a.layout = texture ? usageLayout(a.usage, type) : Layout::Undefined;
    if (type == PassType::Transfer || a.usage == Usage::CopySrc || a.usage == Usage::CopyDst) {
        // Transfer passes (copy, blit, clear) touch everything through the transfer stage.
        a.stages = stage::Copy;
        a.access = (usageReads(a.usage, a.load) ? access::TransferRead : 0u) |
                   (usageWrites(a.usage) ? access::TransferWrite : 0u);
        return;
    }
    switch (a.usage) {
    case Usage::Sampled:
        a.stages = shaderStages;
        a.access = access::ShaderSampledRead;
        break;
    case Usage::UniformRead:
        a.stages = shaderStages;
        a.access = access::UniformRead;
        break;
    case Usage::StorageRead:
        a.stages = shaderStages;
        a.access = access::ShaderStorageRead;
        break;
    case Usage::StorageWrite:
        a.stages = shaderStages;
        a.access = access::ShaderStorageWrite;
        break;
    case Usage::StorageReadWrite:
        a.stages = shaderStages;
        a.access = access::ShaderStorageRead | access::ShaderStorageWrite;
        break;
    case Usage::ColorAttachment:
        a.stages = stage::ColorAttachmentOutput;
        a.access = access::ColorAttachmentWrite | (a.load ? access::ColorAttachmentRead : 0u);
        break;
    case Usage::DepthStencilAttachment:
        a.stages = stage::EarlyFragmentTests | stage::LateFragmentTests;
        a.access = access::DepthStencilWrite | (a.load ? access::DepthStencilRead : 0u);
        break;
    case Usage::DepthStencilRead:
        a.stages = stage::EarlyFragmentTests | stage::LateFragmentTests;
        a.access = access::DepthStencilRead;
        break;
    case Usage::IndirectRead:
        a.stages = stage::DrawIndirect;
        a.access = access::IndirectCommandRead;
        break;
    case Usage::CopySrc:
    case Usage::CopyDst: break;  // handled above
    }
}

// What is known about a resource between passes while planning barriers.
struct SyncState {
    Layout layout = Layout::Undefined;
    uint32_t writeStages = stage::None;  // last write
    uint32_t writeAccess = access::None;
    uint32_t readStages = stage::None;  // reads since the last write
    uint32_t readAccess = access::None;
    uint32_t visibleStages = stage::None;  // made visible to these by a barrier since the last write
    uint32_t visibleAccess = access::None;
};

// barriers: simulate each resource's state through the schedule and emit what each pass needs.
void planBarriers(Compiler& c) {
    auto& resources = c.plan.resources;
    std::vector<SyncState> state(resources.size());
    for (size_t ri = 0; ri < resources.size(); ++ri) {
        if (!resources[ri].imported && !resources[ri].persistent) continue;
        // Whatever happened before the frame: assume any write, textures left ready for sampling.
        state[ri].layout = resources[ri].kind == ResourceKind::Texture ? Layout::ShaderReadOnly : Layout::Undefined;
        state[ri].writeStages = stage::AllCommands;
        state[ri].writeAccess = access::MemoryWrite;
    }

    struct Needed {
        uint32_t resource;
        uint32_t stages = 0, access = 0;
        Layout layout = Layout::Undefined;
        bool reads = false, writes = false;
    };
    for (uint32_t pi = 0; pi < c.plan.passes.size(); ++pi) {
        PlanPass& pass = c.plan.passes[pi];
        std::vector<Needed> needed;
        for (PlanAccess& a : pass.accesses) describeAccess(a, pass.type, resources[a.resource].kind);
        // A depth buffer both sampled and attached read-only is in DepthStencilReadOnly for both.
        for (PlanAccess& a : pass.accesses)
            if (a.usage == Usage::Sampled)
                for (const PlanAccess& b : pass.accesses)
                    if (b.resource == a.resource && b.usage == Usage::DepthStencilRead) a.layout = Layout::DepthStencilReadOnly;
        for (PlanAccess& a : pass.accesses) {
            auto it = std::find_if(needed.begin(), needed.end(), [&](const Needed& n) { return n.resource == a.resource; });
            if (it == needed.end()) it = needed.insert(needed.end(), Needed{a.resource, 0, 0, a.layout});
            it->stages |= a.stages;
            it->access |= a.access;
            it->reads = it->reads || usageReads(a.usage, a.load);
            it->writes = it->writes || usageWrites(a.usage);
        }
        for (const Needed& n : needed) {
            PlanResource& r = resources[n.resource];
            SyncState& s = state[n.resource];
            const bool texture = r.kind == ResourceKind::Texture;
            const bool layoutChange = texture && n.layout != s.layout;
            Barrier b;
            b.resource = n.resource;
            bool emit = false;
            if (r.transient && r.firstPass == static_cast<int32_t>(pi) && !c.aliasPreds[n.resource].empty()) {
                // The memory held another resource: wait for all its users before reusing it.
                emit = true;
                b.aliasedFrom = c.aliasFrom[n.resource];
                for (uint32_t q : c.aliasPreds[n.resource]) {
                    b.srcStages |= resources[q].finalStages;
                    b.srcAccess |= resources[q].finalAccess;
                }
            }
            if (layoutChange || (n.writes && (s.writeStages | s.readStages) != 0)) {
                emit = true;  // transition, WAW or WAR
                b.srcStages |= s.writeStages | s.readStages;
                b.srcAccess |= s.writeAccess;
            } else if (n.reads && s.writeStages != 0 &&
                       ((n.stages & ~s.visibleStages) != 0 || (n.access & ~s.visibleAccess) != 0)) {
                emit = true;  // RAW not yet made visible to these stages
                b.srcStages |= s.writeStages;
                b.srcAccess |= s.writeAccess;
            }
            if (emit) {
                b.dstStages = n.stages;
                b.dstAccess = n.access;
                b.oldLayout = texture ? s.layout : Layout::Undefined;
                b.newLayout = texture ? n.layout : Layout::Undefined;
                pass.barriers.push_back(b);
            }

            if (n.writes) {
                s.writeStages = n.stages;
                s.writeAccess = n.access & kWriteAccessBits;
                s.readStages = s.readAccess = 0;
                s.visibleStages = s.visibleAccess = 0;
            } else if (layoutChange) {
                // The transition waited for every earlier access; only this pass's reads are pending.
                s.readStages = n.stages;
                s.readAccess = n.access;
                s.visibleStages = n.stages;
                s.visibleAccess = n.access;
            } else {
                s.readStages |= n.stages;
                s.readAccess |= n.access;
                if (emit) {
                    s.visibleStages |= n.stages;
                    s.visibleAccess |= n.access;
                }
            }
            if (texture) s.layout = n.layout;
            // Kept current so that later occupants of this memory can wait for it.
            r.finalLayout = s.layout;
            r.finalStages = s.writeStages | s.readStages;
            r.finalAccess = s.writeAccess | s.readAccess;
        }
    }
    // Imported and persistent textures end the frame as they start it: ready for sampling.
    for (uint32_t ri = 0; ri < resources.size(); ++ri) {
        PlanResource& r = resources[ri];
        if ((!r.imported && !r.persistent) || r.kind != ResourceKind::Texture) continue;
        // Already there: a texture in ShaderReadOnly was not written since its last transition
        // (the executor's barrier at the start of each frame orders frames against each other).
        if (r.finalLayout == Layout::ShaderReadOnly) continue;
        if (r.firstPass < 0) continue;
        Barrier b;
        b.resource = ri;
        b.srcStages = r.finalStages;
        b.srcAccess = r.finalAccess & kWriteAccessBits;
        b.dstStages = stage::AllCommands;
        b.dstAccess = access::ShaderSampledRead;
        b.oldLayout = r.finalLayout;
        b.newLayout = Layout::ShaderReadOnly;
        c.plan.finalBarriers.push_back(b);
        r.finalLayout = Layout::ShaderReadOnly;
        r.finalStages = stage::AllCommands;
        r.finalAccess = access::ShaderSampledRead;
    }
}

template <class Fn>
auto timed(Plan& plan, const char* step, Fn&& fn) {
    const auto start = std::chrono::steady_clock::now();
    auto finish = [&] {
        const std::chrono::duration<double, std::milli> ms = std::chrono::steady_clock::now() - start;
        plan.timings.push_back({step, ms.count()});
    };
    if constexpr (std::is_void_v<decltype(fn())>) {
        fn();
        finish();
    } else {
        auto r = fn();
        finish();
        return r;
    }
}

}  // namespace

MemoryRequirements estimateMemoryRequirements(const PlanResource& r) {
    MemoryRequirements m;
    if (r.kind == ResourceKind::Buffer) {
        m.alignment = kBufferAlignment;
        m.size = alignUp(r.bufferSize, kBufferAlignment);
        return m;
    }
    uint64_t texels = 0;
    const uint32_t mips = std::max(r.mips, 1u);
    for (uint32_t level = 0; level < mips; ++level)
        texels += static_cast<uint64_t>(std::max(r.width >> level, 1u)) * std::max(r.height >> level, 1u);
    m.alignment = kTextureAlignment;
    m.size = alignUp(texels * formatInfo(r.format).bytesPerTexel * std::max(r.layers, 1u), kTextureAlignment);
    return m;
}

Result<Plan> compile(const GraphDesc& graph, const CompileOptions& options) {
    Compiler c(graph, options);
    c.plan.outputWidth = options.outputWidth;
    c.plan.outputHeight = options.outputHeight;
    if (auto s = timed(c.plan, "validate", [&] { return validate(c); }); !s)
        return std::unexpected(std::move(s.error()));
    timed(c.plan, "cull", [&] { cull(c); });
    timed(c.plan, "schedule", [&] { schedule(c); });
    timed(c.plan, "lifetimes", [&] { computeLifetimes(c); });
    timed(c.plan, "alias", [&] { alias(c); });
    timed(c.plan, "barriers", [&] { planBarriers(c); });
    return std::move(c.plan);
}

}  // namespace rg

// validate: everything that can be wrong with the declarations (resources, passes, versions,
// cycles), first error in declaration order; it also derives the edges the later steps use.
#include "compiler_steps.h"

#include <algorithm>
#include <cmath>

#include "names.h"

namespace rg::compiler_steps {

namespace {

std::string extentText(Extent e) {
    return std::to_string(e.width) + "x" + std::to_string(e.height);
}

bool isAttachment(Usage u) {
    return u == Usage::ColorAttachment || u == Usage::DepthStencilAttachment ||
           u == Usage::DepthStencilRead;
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

Status invalid(std::string text) { return fail(ErrorCode::InvalidInput, std::move(text)); }

// validate (1/4): names, sizes and formats of the resources.
Status validateResources(Compiler& c) {
    const auto& resources = c.graph.resources;
    for (size_t i = 0; i < resources.size(); ++i) {
        const ResourceDesc& r = resources[i];
        const std::string at = "resources[" + std::to_string(i) + "]";
        if (r.name.empty()) return invalid(withOrigin(r.origin, at + " has no name"));
        if (auto [it, fresh] = c.resourceIndex.emplace(r.name, static_cast<uint32_t>(i)); !fresh)
            return invalid(
                withOrigin(r.origin, "resource '" + r.name + "' is declared twice (resources[" +
                                         std::to_string(it->second) + "] and " + at + ")"));
        const std::string what = "resource '" + r.name + "': ";
        if (r.kind == ResourceKind::Buffer) {
            if (r.buffer.size == 0)
                return invalid(
                    withOrigin(r.origin, what + "buffer size is 0 bytes; it must be at least 1"));
            continue;
        }
        const TextureDesc& t = r.texture;
        if (t.format == Format::Undefined || t.format >= Format::Count)
            return invalid(withOrigin(r.origin, what + "texture has no format (expected one of: " +
                                                    formatNameList() + ")"));
        if (t.sizeMode == SizeMode::Absolute) {
            if (t.width == 0 || t.height == 0)
                return invalid(withOrigin(r.origin, what + "absolute size " +
                                                        std::to_string(t.width) + "x" +
                                                        std::to_string(t.height) +
                                                        "; width and height must be at least 1"));
        } else if (!(t.scaleX > 0.0f) || !(t.scaleY > 0.0f) || !std::isfinite(t.scaleX) ||
                   !std::isfinite(t.scaleY)) {
            return invalid(
                withOrigin(r.origin, what + "output-relative scale " + std::to_string(t.scaleX) +
                                         " x " + std::to_string(t.scaleY) + " must be positive"));
        }
        const Extent e = resolveExtent(t, c.options);
        if (e.width > kMaxDimension || e.height > kMaxDimension)
            return invalid(withOrigin(r.origin, what + "size " + extentText(e) + " exceeds " +
                                                    std::to_string(kMaxDimension) + " texels"));
        if (t.layers == 0)
            return invalid(withOrigin(r.origin, what + "layers is 0; it must be at least 1"));
        if (t.cube) {
            if (e.width != e.height)
                return invalid(withOrigin(
                    r.origin, what + "a cube texture must be square, got " + extentText(e)));
            if (t.layers != 1 && t.layers % 6 != 0)
                return invalid(
                    withOrigin(r.origin, what + "a cube texture has 6 layers per cube, got " +
                                             std::to_string(t.layers)));
        }
        if (t.mips > fullMipChain(e))
            return invalid(withOrigin(r.origin, what + std::to_string(t.mips) +
                                                    " mips requested, but a " + extentText(e) +
                                                    " texture has at most " +
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
            return use + " needs a raster pass (indirect draws), but '" + pass.name + "' is a " +
                   passTypeName(pass.type) + " pass";
        if (a.usage == Usage::UniformRead || isStorage(a.usage) || a.usage == Usage::CopySrc ||
            a.usage == Usage::CopyDst || a.usage == Usage::IndirectRead)
            return {};
        return "'" + r.name + "' is a buffer, which cannot be used as " + use +
               " (expected UniformRead, StorageRead, StorageWrite, StorageReadWrite, IndirectRead, "
               "CopySrc or CopyDst)";
    }
    if (a.usage == Usage::IndirectRead)
        return "'" + r.name +
               "' is a texture, which cannot be used as IndirectRead (indirect commands live in "
               "buffers)";
    if (a.usage == Usage::UniformRead)
        return "'" + r.name +
               "' is a texture, which cannot be used as UniformRead (uniform reads are for "
               "buffers)";
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
               " (sRGB formats cannot be storage images; use a UNORM format and encode in the "
               "shader)";
    if (f.integer && a.usage == Usage::ColorAttachment && truthy(pass.params["blend"]))
        return "'" + r.name + "' has integer format " + fmt +
               ", which cannot be a blended ColorAttachment (params.blend is set)";
    return {};
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
                                                    std::to_string(it->second) + "] and " + at +
                                                    ")"));
    }

    for (uint32_t pi = 0; pi < passes.size(); ++pi) {
        const PassDesc& p = passes[pi];
        auto& resolved = c.accessResource[pi];
        for (uint32_t ai = 0; ai < p.accesses.size(); ++ai) {
            const Access& a = p.accesses[ai];
            // Built only on the error path: validation runs on every recompile.
            auto where = [&] {
                return "pass '" + p.name + "' field '" + c.fieldOf(pi, ai) + "': ";
            };
            const auto found = c.resourceIndex.find(a.resource);
            const ResourceDesc* r =
                found == c.resourceIndex.end() ? nullptr : &resources[found->second];
            if (!r)
                return invalid(c.passError(
                    pi, where() + "unknown resource '" + a.resource + "'" +
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
                    return invalid(c.passError(pi, where() + "'" + r->name +
                                                       "' is already written as " + other +
                                                       " in this pass"));
                if (usageWrites(a.usage) || usageWrites(b.usage))
                    return invalid(c.passError(
                        pi, where() + "'" + r->name + "' is used as " + usageName(a.usage) +
                                " and also as " + other + " in the same pass (feedback loop)"));
                // Sampling a depth buffer that is also the read-only depth/stencil attachment is
                // fine: both read, in DepthStencilReadOnly (deferred lighting tests stencil and
                // reads depth for positions).
                const bool depthReadAndSample =
                    (a.usage == Usage::Sampled && b.usage == Usage::DepthStencilRead) ||
                    (a.usage == Usage::DepthStencilRead && b.usage == Usage::Sampled);
                if (r->kind == ResourceKind::Texture && !depthReadAndSample &&
                    usageLayout(a.usage, p.type) != usageLayout(b.usage, p.type))
                    return invalid(
                        c.passError(pi, where() + "'" + r->name + "' is used as " +
                                            usageName(a.usage) + " and also as " + other +
                                            " in the same pass, which need different layouts"));
            }
            resolved.push_back(ri);
            auto m = std::find_if(c.merged[pi].begin(), c.merged[pi].end(),
                                  [&](const MergedAccess& x) { return x.resource == ri; });
            if (m == c.merged[pi].end())
                m = c.merged[pi].insert(c.merged[pi].end(), MergedAccess{ri});
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
                        pi,
                        "pass '" + p.name + "' field '" + c.fieldOf(pi, ai) + "': '" +
                            p.accesses[ai].resource +
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
                    return invalid(
                        c.passError(pi, "pass '" + p.name + "': attachments differ in size: '" +
                                            ra.name + "' is " + extentText(ea) + " but '" +
                                            rb.name + "' is " + extentText(eb)));
            }
        }

        for (size_t k = 0; k < p.after.size(); ++k) {
            if (c.passIndex.contains(p.after[k])) continue;
            return invalid(c.passError(
                pi, "pass '" + p.name + "' field 'after[" + std::to_string(k) +
                        "]': unknown pass '" + p.after[k] + "'" +
                        suggestionAmong(
                            p.after[k], passes,
                            [](const PassDesc& d) -> const std::string& { return d.name; })));
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
    std::vector<std::vector<uint32_t>> disabledWriters(resources.size());
    std::vector<std::vector<uint32_t>> readers(resources.size());
    // "its only writer 'a' is disabled" / "its writers 'a' and 'b' are disabled"
    auto disabledText = [&](size_t resource) {
        const auto& list = disabledWriters[resource];
        std::string names;
        for (size_t i = 0; i < list.size(); ++i)
            names += (i == 0                 ? ""
                      : i + 1 == list.size() ? " and "
                                             : ", ") +
                     ("'" + passes[list[i]].name + "'");
        return list.size() == 1 ? "its only writer " + names + " is disabled"
                                : "its writers " + names + " are disabled";
    };

    for (uint32_t pi = 0; pi < passCount; ++pi) {
        const PassDesc& p = passes[pi];
        if (!p.enabled) {
            for (const MergedAccess& m : c.merged[pi])
                if (m.writes) disabledWriters[m.resource].push_back(pi);
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
                if (!disabledWriters[m.resource].empty())
                    return invalid(c.passError(pi, "pass '" + p.name + "' reads '" + r.name +
                                                       "', but " + disabledText(m.resource)));
                std::string text =
                    "pass '" + p.name + "' reads '" + r.name + "' before any pass writes it";
                for (uint32_t later = pi + 1; later < passCount; ++later) {
                    if (!passes[later].enabled) continue;
                    const auto& lm = c.merged[later];
                    if (std::any_of(lm.begin(), lm.end(), [&](const MergedAccess& x) {
                            return x.resource == m.resource && x.writes;
                        })) {
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
                const bool ordered =
                    std::find(p.after.begin(), p.after.end(), writer) != p.after.end();
                if (!m.reads && !r.imported && !r.persistent && !ordered)
                    return invalid(c.passError(
                        pi, "passes '" + writer + "' and '" + p.name + "' both write '" + r.name +
                                "' with no order between them: make '" + p.name +
                                "' load it or list '" + writer + "' in its after"));
                c.addEdge(static_cast<uint32_t>(w), pi, /* need= */ true);
            }
            for (uint32_t q : readers[m.resource])
                if (q != pi) c.addEdge(q, pi, /* need= */ false);
            readers[m.resource].clear();
            lastWriter[m.resource] = static_cast<int32_t>(pi);
        }
    }
    // An output (or a capture) whose only writers are switched off would be read back unwritten.
    for (size_t r = 0; r < resources.size(); ++r) {
        const ResourceDesc& res = resources[r];
        if (!res.exported || res.imported || res.persistent || lastWriter[r] >= 0 ||
            disabledWriters[r].empty())
            continue;
        const uint32_t writer = disabledWriters[r].back();
        return invalid(c.passError(writer, "'" + res.name +
                                               "' is exported (an output or a capture) but not "
                                               "written: " +
                                               disabledText(r)));
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
                std::rotate(cycle.begin(), std::min_element(cycle.begin(), cycle.end()),
                            cycle.end());
                std::string text = "cycle between passes: ";
                for (uint32_t p : cycle) text += "'" + c.graph.passes[p].name + "' -> ";
                text += "'" + c.graph.passes[cycle.front()].name + "'";
                return invalid(c.passError(cycle.front(), text));
            }
        }
    }
    return {};
}

}  // namespace

// validate: everything that can be wrong with the declarations, first error in declaration order.
Status validate(Compiler& c) {
    if (auto s = validateResources(c); !s) return s;
    if (auto s = validatePasses(c); !s) return s;
    if (auto s = validateVersions(c); !s) return s;
    return validateCycles(c);
}

}  // namespace rg::compiler_steps

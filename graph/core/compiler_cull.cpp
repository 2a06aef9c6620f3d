// cull and schedule: the passes that run (reference counting from the roots, with the reason
// each culled pass gives) and their order.
#include "compiler_steps.h"

#include <algorithm>
#include <functional>
#include <queue>

#include "check.h"

namespace rg::compiler_steps {

namespace {

std::string quotedList(const std::vector<std::string>& names) {
    std::string s;
    for (size_t i = 0; i < names.size(); ++i) {
        if (i > 0) s += i + 1 == names.size() ? " and " : ", ";
        s += "'" + names[i] + "'";
    }
    return s;
}

}  // namespace

// cull: keep side-effect passes and writers of exported/imported/persistent resources, and
// what they need; then the keep passes of the histories a kept pass reads.
void cull(Compiler& c) {
    const auto& passes = c.graph.passes;
    const auto& resources = c.graph.resources;
    c.kept.assign(passes.size(), false);
    std::vector<uint32_t> work;
    for (uint32_t pi = 0; pi < passes.size(); ++pi) {
        if (!passes[pi].enabled) continue;
        bool root = passes[pi].sideEffect;
        for (const MergedAccess& m : c.merged[pi]) {
            const ResourceDesc& r = resources[m.resource];
            root = root || (m.writes &&
                            (r.exported || r.imported || (r.persistent && r.historyOf.empty())));
        }
        if (root) {
            c.kept[pi] = true;
            work.push_back(pi);
        }
    }
    // Only RAW, WAW and `after` edges keep a pass: a WAR edge orders a reader before the next
    // writer, but that writer does not need the reader's work.
    auto propagate = [&] {
        while (!work.empty()) {
            const uint32_t p = work.back();
            work.pop_back();
            for (uint32_t q : c.needs[p]) {
                if (c.kept[q]) continue;
                c.kept[q] = true;
                work.push_back(q);
            }
        }
    };
    propagate();
    // A history (rg.resource's `history`) is read the frame after it is written, which no edge
    // says: the passes writing one (its keep passes) stay while a kept pass reads it — without
    // a reader (TAA switched off) the copy is not made.
    auto readByKept = [&](uint32_t resource) {
        for (uint32_t q = 0; q < passes.size(); ++q)
            if (c.kept[q])
                for (const MergedAccess& m : c.merged[q])
                    if (m.resource == resource && m.reads) return true;
        return false;
    };
    for (bool more = true; more;) {
        more = false;
        for (uint32_t pi = 0; pi < passes.size(); ++pi) {
            if (c.kept[pi] || !passes[pi].enabled) continue;
            for (const MergedAccess& m : c.merged[pi])
                if (m.writes && !resources[m.resource].historyOf.empty() &&
                    readByKept(m.resource)) {
                    c.kept[pi] = true;
                    work.push_back(pi);
                    more = true;
                    break;
                }
        }
        propagate();
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

}  // namespace rg::compiler_steps

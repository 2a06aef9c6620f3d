#include "plan.h"

#include <cstdio>
#include <utility>

#include <nlohmann/json.hpp>

namespace rg {

namespace {

struct BitName {
    uint32_t bit;
    const char* name;
};

// Same order as the enums in plan.h, so masks print in a stable, readable order.
constexpr BitName kStageNames[] = {
    {stage::VertexShader, "VertexShader"},
    {stage::FragmentShader, "FragmentShader"},
    {stage::ComputeShader, "ComputeShader"},
    {stage::EarlyFragmentTests, "EarlyFragmentTests"},
    {stage::LateFragmentTests, "LateFragmentTests"},
    {stage::ColorAttachmentOutput, "ColorAttachmentOutput"},
    {stage::Copy, "Copy"},
    {stage::Host, "Host"},
    {stage::AllCommands, "AllCommands"},
    {stage::DrawIndirect, "DrawIndirect"},
};

constexpr BitName kAccessNames[] = {
    {access::ShaderSampledRead, "ShaderSampledRead"},
    {access::ShaderStorageRead, "ShaderStorageRead"},
    {access::ShaderStorageWrite, "ShaderStorageWrite"},
    {access::UniformRead, "UniformRead"},
    {access::ColorAttachmentRead, "ColorAttachmentRead"},
    {access::ColorAttachmentWrite, "ColorAttachmentWrite"},
    {access::DepthStencilRead, "DepthStencilRead"},
    {access::DepthStencilWrite, "DepthStencilWrite"},
    {access::TransferRead, "TransferRead"},
    {access::TransferWrite, "TransferWrite"},
    {access::HostRead, "HostRead"},
    {access::HostWrite, "HostWrite"},
    {access::MemoryWrite, "MemoryWrite"},
    {access::IndirectCommandRead, "IndirectCommandRead"},
};

template <size_t N>
std::string maskName(uint32_t mask, const BitName (&names)[N]) {
    if (mask == 0) return "None";
    std::string s;
    uint32_t known = 0;
    for (const auto& n : names) {
        known |= n.bit;
        if ((mask & n.bit) == 0) continue;
        if (!s.empty()) s += "|";
        s += n.name;
    }
    // Unknown bits would be a bug elsewhere; show them instead of hiding them.
    if (uint32_t rest = mask & ~known) {
        char buf[16];
        std::snprintf(buf, sizeof buf, "0x%x", rest);
        if (!s.empty()) s += "|";
        s += buf;
    }
    return s;
}

// DOT strings are double-quoted; names come from scripts and may hold anything.
std::string dotEscape(const std::string& s) {
    std::string out;
    out.reserve(s.size());
    for (char c : s) {
        if (c == '"' || c == '\\') out += '\\';
        if (c == '\n') {
            out += "\\n";
            continue;
        }
        out += c;
    }
    return out;
}

std::string bytesText(uint64_t bytes) {
    char buf[64];
    if (bytes >= (1ull << 20))
        std::snprintf(buf, sizeof buf, "%.2f MiB", static_cast<double>(bytes) / double(1ull << 20));
    else if (bytes >= (1ull << 10))
        std::snprintf(buf, sizeof buf, "%.1f KiB", static_cast<double>(bytes) / double(1ull << 10));
    else
        std::snprintf(buf, sizeof buf, "%llu B", static_cast<unsigned long long>(bytes));
    return buf;
}

// DOT-ready label (already escaped): name, format and size, lifetime, placement.
std::string resourceLabel(const PlanResource& r) {
    std::string label = dotEscape(r.name) + "\\n";
    if (r.kind == ResourceKind::Buffer) {
        label += "buffer " + std::to_string(r.bufferSize) + " B";
    } else {
        label += std::string(formatName(r.format)) + " " + std::to_string(r.width) + "x" +
                 std::to_string(r.height);
        if (r.layers != 1)
            label += " x" + std::to_string(r.layers) + (r.cube ? " (cube)" : " layers");
        if (r.mips != 1) label += " " + std::to_string(r.mips) + " mips";
    }
    label += "\\npasses " + std::to_string(r.firstPass) + ".." + std::to_string(r.lastPass);
    if (r.imported) label += "\\nimported";
    if (r.exported) label += r.imported ? ", exported" : "\\nexported";
    if (r.heap >= 0)
        label += "\\nheap " + std::to_string(r.heap) + " @ " + std::to_string(r.offset) + " (" +
                 bytesText(r.memory.size) + ")";
    else if (!r.imported)
        label += "\\nown allocation (" + bytesText(r.memory.size) + ")";
    return label;
}

}  // namespace

const char* layoutName(Layout l) {
    switch (l) {
        case Layout::Undefined:
            return "Undefined";
        case Layout::General:
            return "General";
        case Layout::ColorAttachment:
            return "ColorAttachment";
        case Layout::DepthStencilAttachment:
            return "DepthStencilAttachment";
        case Layout::DepthStencilReadOnly:
            return "DepthStencilReadOnly";
        case Layout::ShaderReadOnly:
            return "ShaderReadOnly";
        case Layout::TransferSrc:
            return "TransferSrc";
        case Layout::TransferDst:
            return "TransferDst";
    }
    return "?";
}

std::string stageMaskName(uint32_t mask) { return maskName(mask, kStageNames); }
std::string accessMaskName(uint32_t mask) { return maskName(mask, kAccessNames); }

int32_t Plan::findResource(const std::string& name) const {
    for (size_t i = 0; i < resources.size(); ++i)
        if (resources[i].name == name) return static_cast<int32_t>(i);
    return -1;
}

int32_t Plan::findPass(const std::string& name) const {
    for (size_t i = 0; i < passes.size(); ++i)
        if (passes[i].name == name) return static_cast<int32_t>(i);
    return -1;
}

std::string Plan::toDot() const {
    std::string out =
        "digraph rgraph {\n  rankdir=LR;\n  node [fontname=\"Helvetica\", fontsize=10];\n";
    out += "  label=\"output " + std::to_string(outputWidth) + "x" + std::to_string(outputHeight) +
           ", transient memory " + bytesText(transientBytesAliased) + " aliased / " +
           bytesText(transientBytesUnaliased) + " unaliased\";\n";

    for (size_t i = 0; i < passes.size(); ++i) {
        const PlanPass& p = passes[i];
        out += "  \"p_" + dotEscape(p.name) +
               "\" [shape=box, style=filled, fillcolor=\"#dde8ff\", label=\"#" + std::to_string(i) +
               " " + dotEscape(p.name) + "\\n" + dotEscape(p.kind) + " (" + passTypeName(p.type) +
               ")\"];\n";
    }
    // Culled passes keep no accesses in the plan, so they stand alone with the reason.
    for (const CulledPass& c : culled)
        out += "  \"p_" + dotEscape(c.name) +
               "\" [shape=box, style=dashed, color=grey, fontcolor=grey, label=\"" +
               dotEscape(c.name) + "\\nculled: " + dotEscape(c.reason) + "\"];\n";
    // Invisible chain so Graphviz lays the passes out in execution order.
    for (size_t i = 1; i < passes.size(); ++i)
        out += "  \"p_" + dotEscape(passes[i - 1].name) + "\" -> \"p_" + dotEscape(passes[i].name) +
               "\" [style=invis];\n";

    for (const PlanResource& r : resources) {
        const char* fill = r.imported ? "#ffe0b0" : r.exported ? "#d0f0c0" : "#f4f4f4";
        out += "  \"r_" + dotEscape(r.name) + "\" [shape=ellipse, style=filled, fillcolor=\"" +
               fill + "\", label=\"" + resourceLabel(r) + "\"];\n";
    }

    for (const PlanPass& p : passes) {
        for (const PlanAccess& a : p.accesses) {
            const std::string res = "\"r_" + dotEscape(resources[a.resource].name) + "\"";
            const std::string pass = "\"p_" + dotEscape(p.name) + "\"";
            const bool reads = usageReads(a.usage, a.load);
            const bool writes = usageWrites(a.usage);
            if (reads)
                out += "  " + res + " -> " + pass + " [color=\"#2060c0\", label=\"" +
                       usageName(a.usage) + "\", fontsize=8];\n";
            if (writes)
                out += "  " + pass + " -> " + res + " [color=\"#c03020\", label=\"" +
                       usageName(a.usage) + "\", fontsize=8];\n";
        }
    }
    out += "}\n";
    return out;
}

std::string Plan::toJson() const {
    // ordered_json keeps the documented key order, so a dump reads top-down like the plan.
    using json = nlohmann::ordered_json;
    auto resourceName = [&](uint32_t i) -> json {
        return i < resources.size() ? json(resources[i].name) : json(nullptr);
    };

    json j;
    j["output"] = {{"w", outputWidth}, {"h", outputHeight}};

    json jpasses = json::array();
    for (const PlanPass& p : passes) {
        json jp;
        jp["name"] = p.name;
        jp["kind"] = p.kind;
        jp["type"] = passTypeName(p.type);
        json acc = json::array();
        for (const PlanAccess& a : p.accesses)
            acc.push_back({{"resource", resourceName(a.resource)},
                           {"usage", usageName(a.usage)},
                           {"load", a.load},
                           {"layout", layoutName(a.layout)},
                           {"stages", stageMaskName(a.stages)},
                           {"access", accessMaskName(a.access)}});
        jp["accesses"] = std::move(acc);
        json bars = json::array();
        for (const Barrier& b : p.barriers)
            bars.push_back({{"resource", resourceName(b.resource)},
                            {"srcStages", stageMaskName(b.srcStages)},
                            {"srcAccess", accessMaskName(b.srcAccess)},
                            {"dstStages", stageMaskName(b.dstStages)},
                            {"dstAccess", accessMaskName(b.dstAccess)},
                            {"oldLayout", layoutName(b.oldLayout)},
                            {"newLayout", layoutName(b.newLayout)},
                            {"aliasedFrom", b.aliasedFrom >= 0
                                                ? resourceName(static_cast<uint32_t>(b.aliasedFrom))
                                                : json(nullptr)}});
        jp["barriers"] = std::move(bars);
        jpasses.push_back(std::move(jp));
    }
    j["passes"] = std::move(jpasses);

    json jculled = json::array();
    for (const CulledPass& c : culled) jculled.push_back({{"name", c.name}, {"reason", c.reason}});
    j["culled"] = std::move(jculled);

    json jres = json::array();
    for (const PlanResource& r : resources) {
        const bool buffer = r.kind == ResourceKind::Buffer;
        jres.push_back(
            {{"name", r.name},
             {"kind", buffer ? "buffer" : "texture"},
             {"format", buffer ? json(nullptr) : json(std::string(formatName(r.format)))},
             {"width", r.width},
             {"height", r.height},
             {"layers", r.layers},
             {"mips", r.mips},
             {"cube", r.cube},
             {"bufferSize", r.bufferSize},
             {"transient", r.transient},
             {"imported", r.imported},
             {"exported", r.exported},
             {"firstPass", r.firstPass},
             {"lastPass", r.lastPass},
             {"size", r.memory.size},
             {"alignment", r.memory.alignment},
             {"memoryTypeBits", r.memory.memoryTypeBits},
             {"heap", r.heap},
             {"offset", r.offset},
             {"finalLayout", layoutName(r.finalLayout)},
             {"finalStages", stageMaskName(r.finalStages)},
             {"finalAccess", accessMaskName(r.finalAccess)}});
    }
    j["resources"] = std::move(jres);

    json jheaps = json::array();
    for (const TransientHeap& h : heaps)
        jheaps.push_back(
            {{"memoryTypeBits", h.memoryTypeBits}, {"buffers", h.buffers}, {"size", h.size}});
    j["heaps"] = std::move(jheaps);
    j["transientBytesAliased"] = transientBytesAliased;
    j["transientBytesUnaliased"] = transientBytesUnaliased;

    json jt = json::array();
    for (const StepTiming& t : timings) jt.push_back({{"step", t.step}, {"ms", t.ms}});
    j["timings"] = std::move(jt);
    return j.dump(2);
}

}  // namespace rg

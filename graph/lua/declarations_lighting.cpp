// rg.stencil and rg.path: stencil classes with their values (and variants in the high bits), and
// the lighting paths that light a stencil class.
#include "declarations_detail.h"

#include <algorithm>
#include <map>
#include <vector>

namespace rg::declarations {

// Classes of their own take the low `stencilBits` (explicit values first, then the lowest
// free value in declaration order); variants (`variant_of`) keep their base's low bits and
// take the lowest free value in the high bits, so a class's value never depends on another
// class's explicit value.
Result<void> Builder::stencils() {
    const uint32_t bits = options.stencilBits;
    const uint32_t capacity = (1u << bits) - 1;
    const uint32_t variants = (1u << (8 - bits)) - 1;
    std::map<uint32_t, const Declaration*> taken;
    std::map<std::string, const Declaration*> byName;
    for (int pass = 0; pass < 3; ++pass) {
        for (const auto& d : decls) {
            if (d.kind != DeclKind::Stencil) continue;
            Where w = where(d);
            if (pass == 0) {
                if (auto r = checkFields(w, d.body, {"value", "variant_of", "doc"}); !r) return r;
                if (d.body.has("variant_of") && d.body.has("value"))
                    return w.at("value").error(
                        "a variant takes its base's value in the low bits and is allocated the "
                        "high bits; give no value");
                if (d.body.has("doc"))
                    if (auto r = expectType(w.at("doc"), d.body["doc"], "string"); !r) return r;
            }
            const bool variant = d.body.has("variant_of");
            const bool explicitValue = d.body.has("value");
            if (pass != (variant ? 2 : explicitValue ? 0 : 1)) continue;
            StencilClassDesc c{fullName(d), 0, capacity, "", d.body["doc"].asString(), d.origin};
            if (variant) {
                if (auto r = expectType(w.at("variant_of"), d.body["variant_of"], "string"); !r)
                    return r;
                const std::string baseName = d.body["variant_of"].asString();
                auto base = std::find_if(out.stencilClasses.begin(), out.stencilClasses.end(),
                                         [&](auto& s) { return s.name == baseName; });
                if (base == out.stencilClasses.end()) {
                    std::vector<std::string> names;
                    for (const auto& s : out.stencilClasses) names.push_back(s.name);
                    return w.at("variant_of")
                        .error("unknown stencil class '" + baseName + "'" +
                               suggestion(baseName, names) +
                               (names.empty() ? "" : "; expected one of: " + joinQuoted(names)));
                }
                if (!base->base.empty())
                    return w.at("variant_of")
                        .error("'" + baseName + "' is itself a variant of '" + base->base +
                               "'; name a class of its own");
                uint32_t k = 1;
                while (k <= variants && taken.count(base->value | (k << bits))) ++k;
                if (k > variants)
                    return w.error("no variant of '" + baseName + "' left: the high " +
                                   std::to_string(8 - bits) + " stencil bits hold " +
                                   std::to_string(variants) + " variants per class");
                c.value = base->value | (k << bits);
                c.mask = 0xFFu;
                c.base = base->name;
            } else if (explicitValue) {
                const Value& v = d.body["value"];
                if (!isInteger(v) || v.asNumber() < 1 || v.asNumber() > capacity)
                    return w.at("value").error("expected a whole number in 1.." +
                                               std::to_string(capacity) + " (" +
                                               std::to_string(bits) +
                                               " stencil bits for classes; a class lit as another "
                                               "is a variant: variant_of = \"class\")");
                c.value = static_cast<uint32_t>(v.asNumber());
                if (taken.count(c.value))
                    return w.at("value").error(
                        std::to_string(c.value) + " is already the value of stencil class '" +
                        fullName(*taken[c.value]) + "' (" + taken[c.value]->origin + ")");
            } else {
                for (c.value = 1; c.value <= capacity && taken.count(c.value); ++c.value) {
                }
                if (c.value > capacity) {
                    std::vector<std::string> names;
                    for (auto& [_, td] : taken) names.push_back(fullName(*td));
                    return w.error("no stencil value left: " + std::to_string(bits) +
                                   " stencil bits hold " + std::to_string(capacity) +
                                   " classes, all taken by " + joinQuoted(names));
                }
            }
            taken[c.value] = &d;
            out.stencilClasses.push_back(c);
        }
    }
    // Keep declaration order in the result.
    std::vector<StencilClassDesc> ordered;
    for (const auto& d : decls)
        for (const auto& s : out.stencilClasses)
            if (d.kind == DeclKind::Stencil && s.name == fullName(d)) ordered.push_back(s);
    out.stencilClasses = ordered;
    return {};
}

bool Builder::hasStencil(const std::string& n) const {
    return std::any_of(out.stencilClasses.begin(), out.stencilClasses.end(),
                       [&](auto& s) { return s.name == n; });
}
std::vector<std::string> Builder::stencilNames() const {
    std::vector<std::string> v;
    for (auto& s : out.stencilClasses) v.push_back(s.name);
    return v;
}

Result<void> Builder::path(const Declaration& d) {
    Where w = where(d);
    if (auto r = checkFields(w, d.body, {"stencil", "shading", "doc"}); !r) return r;
    // Without a stencil class a path is the forward pass's only (a material drawn forward, such as
    // the transmission): no deferred lighting pass lights it, and it takes no class.
    std::string stencil;
    if (d.body.has("stencil")) {
        if (auto r = expectType(w.at("stencil"), d.body["stencil"], "string"); !r) return r;
        stencil = d.body["stencil"].asString();
        if (!hasStencil(stencil))
            return w.at("stencil").error("unknown stencil class '" + stencil + "'" +
                                         suggestion(stencil, stencilNames()));
    }
    std::string shading;
    if (d.body.has("shading")) {
        if (auto r = expectType(w.at("shading"), d.body["shading"], "string"); !r) return r;
        // Next to the declaring script (a game team's folder), else the shader include folders.
        shading = nextToDeclaration(d.origin, d.body["shading"].asString(), options.projectRoot);
    }
    out.lightingPaths.push_back(
        {fullName(d), stencil, shading, d.body["doc"].asString(), d.origin});
    return {};
}

}  // namespace rg::declarations

// rg.material: id, layout, surface, lighting path, stencil, fills and fix-up, standard channels,
// decals and params; then each material's identity (its stencil value) and the passes' material
// choices.
#include "declarations_detail.h"

#include <algorithm>
#include <map>
#include <set>
#include <vector>

namespace rg::declarations {

// `channels = { baseColor = "diffuseColor" }`: which of the layout's channels holds each
// standard parameter (kStandardChannels) where the name differs; the rest by their own name.
// `decals = { "normal", ... }` (or false): the standard parameters decals blend; by default
// the seed's common set that the layout holds (000 §3.3: Normal, BaseColor, Smoothness).
Result<void> Builder::standardChannels(const Where& w, const Value& b, const LayoutDesc& layout,
                                       MaterialDesc& m) {
    auto channel = [&](const std::string& name) -> const ChannelDesc* {
        for (const auto& t : layout.targets)
            for (const auto& c : t.channels)
                if (c.name == name) return &c;
        return nullptr;
    };
    // What each standard parameter needs of its channel: components, and a float encoding.
    auto fits = [&](const std::string& standard, const ChannelDesc& c) {
        const bool vec3 = standard == "normal" || standard == "baseColor" || standard == "f0" ||
                          standard == "emissive";
        if (c.encoding == Encoding::Uint) return false;
        if (standard == "normal")
            return c.encoding == Encoding::Oct ||
                   (c.encoding == Encoding::Snorm && valueComponents(c) == 3);
        return valueComponents(c) == (vec3 ? 3u : 1u);
    };
    std::vector<std::string> standard(std::begin(kStandardChannels), std::end(kStandardChannels));
    if (b.has("channels")) {
        if (auto r = expectType(w.at("channels"), b["channels"], "table"); !r) return r;
        for (const auto& [key, value] : b["channels"].asTable()) {
            const Where cw = w.at("channels").at(key);
            if (std::find(standard.begin(), standard.end(), key) == standard.end())
                return cw.error("not a standard parameter" + suggestion(key, standard) +
                                "; expected one of: " + joinQuoted(standard));
            if (!value.isString())
                return cw.error("expected the name of a channel of layout '" + layout.name + "'");
            m.channels[key] = value.asString();
        }
    }
    for (const auto& s : standard) {
        const bool declared = m.channels.count(s) > 0;
        const std::string name = declared ? m.channels[s] : s;
        const ChannelDesc* c = channel(name);
        if (!c) {
            if (declared) {
                std::vector<std::string> names;
                for (const auto& t : layout.targets)
                    for (const auto& ch : t.channels) names.push_back(ch.name);
                return w.at("channels")
                    .at(s)
                    .error("layout '" + layout.name + "' has no channel '" + name + "'" +
                           suggestion(name, names));
            }
            continue;
        }
        if (!fits(s, *c)) {
            if (declared)
                return w.at("channels")
                    .at(s)
                    .error("channel '" + name + "' (" + std::string(encodingName(c->encoding)) +
                           ", " + std::to_string(valueComponents(*c)) +
                           " components) cannot hold " + s);
            continue;  // a channel of the same name but another meaning: not the standard one
        }
        m.channels[s] = name;
    }
    std::vector<std::string> allowed(std::begin(kDecalParameters), std::end(kDecalParameters));
    if (!b.has("decals")) {
        for (const char* s : {"normal", "baseColor", "smoothness"})
            if (m.channels.count(s)) m.decals.push_back(s);
        return {};
    }
    const Value& dv = b["decals"];
    if (dv.isBool() && !dv.asBool()) return {};
    auto list = stringList(w.at("decals"), dv);
    if (!list) return std::unexpected(list.error());
    for (size_t i = 0; i < list->size(); ++i) {
        const std::string& s = (*list)[i];
        if (std::find(allowed.begin(), allowed.end(), s) == allowed.end())
            return w.at("decals").index(i).error("decals blend " + joinQuoted(allowed) +
                                                 suggestion(s, allowed) + "; not '" + s + "'");
        if (!m.channels.count(s))
            return w.at("decals").index(i).error(
                "layout '" + layout.name + "' has no channel for " + s +
                " (name it in channels = { " + s + " = \"...\" }), so decals cannot blend it");
        m.decals.push_back(s);
    }
    return {};
}

Result<void> Builder::material(const Declaration& d) {
    Where w = where(d);
    const Value& b = d.body;
    if (auto r = checkFields(w, b,
                             {"id", "layout", "surface", "path", "stencil", "fills", "fixup",
                              "params", "textures", "channels", "decals", "forward", "doc"});
        !r)
        return r;
    MaterialDesc m;
    m.name = fullName(d);
    m.origin = d.origin;
    // `id`: what the surface writes as RG_MATERIAL_ID into a layout's materialId channel, if it
    // keeps one; no reader decodes by it (a pixel's material is its stencil value).
    if (b.has("id") && (!isInteger(b["id"]) || b["id"].asNumber() < 0))
        return w.at("id").error("expected a whole number >= 0");
    m.id = b.has("id") ? static_cast<uint32_t>(b["id"].asNumber()) : 0;
    auto layoutName = requireString(w, b, "layout");
    if (!layoutName) return std::unexpected(layoutName.error());
    auto lit = std::find_if(out.layouts.begin(), out.layouts.end(), [&](auto& l) {
        return !d.module.empty() && l.name == d.module + "_" + *layoutName;
    });
    if (lit == out.layouts.end())
        lit = std::find_if(out.layouts.begin(), out.layouts.end(),
                           [&](auto& l) { return l.name == *layoutName; });
    if (lit == out.layouts.end()) {
        std::vector<std::string> names;
        for (auto& l : out.layouts) names.push_back(l.name);
        return w.at("layout").error("unknown layout '" + *layoutName + "'" +
                                    suggestion(*layoutName, names));
    }
    m.layout = lit->name;
    // The id must fit the layout's materialId field.
    for (const auto& t : lit->targets)
        for (const auto& c : t.channels)
            if (c.name == "materialId" && c.encoding == Encoding::Uint && c.bits < 32 &&
                m.id >= (1u << c.bits))
                return w.at("id").error(std::to_string(m.id) + " does not fit layout '" + m.layout +
                                        "': its materialId has " + std::to_string(c.bits) +
                                        " bits (ids 0.." + std::to_string((1u << c.bits) - 1) +
                                        ")");
    for (const char* field : {"surface", "path", "stencil", "fixup"})
        if (b.has(field))
            if (auto r = expectType(w.at(field), b[field], "string"); !r) return r;
    m.surface = b["surface"].asString();
    // A surface file next to the declaring script (a game team's folder) is found there;
    // otherwise the shader include folders are searched (materials/, shaders/).
    if (!m.surface.empty()) m.surface = nextToDeclaration(d.origin, m.surface, options.projectRoot);
    m.path = b["path"].asString();
    if (!m.path.empty()) {
        auto pit = std::find_if(out.lightingPaths.begin(), out.lightingPaths.end(),
                                [&](auto& p) { return p.name == m.path; });
        if (pit == out.lightingPaths.end()) {
            std::vector<std::string> names;
            for (auto& p : out.lightingPaths) names.push_back(p.name);
            return w.at("path").error("unknown lighting path '" + m.path + "'" +
                                      suggestion(m.path, names));
        }
        m.stencil = pit->stencil;
    }
    if (b.has("stencil")) {
        m.stencil = b["stencil"].asString();
        if (!hasStencil(m.stencil))
            return w.at("stencil").error("unknown stencil class '" + m.stencil + "'" +
                                         suggestion(m.stencil, stencilNames()));
    }
    auto fills = stringList(w.at("fills"), b["fills"]);
    if (!fills) return std::unexpected(fills.error());
    for (size_t i = 0; i < fills->size(); ++i) {
        std::vector<std::string> targets;
        for (auto& t : lit->targets) targets.push_back(t.name);
        if (std::find(targets.begin(), targets.end(), (*fills)[i]) == targets.end())
            return w.at("fills").index(i).error("layout '" + m.layout + "' has no target '" +
                                                (*fills)[i] + "'" +
                                                suggestion((*fills)[i], targets));
    }
    m.fills = *fills;
    // `forward = true`: a material whose shading needs what lies behind it (a transmission's
    // refraction of the opaque frame) is drawn by the forward pass only, never into the G-buffer.
    if (b.has("forward")) {
        if (!b["forward"].isBool()) return w.at("forward").error("expected a boolean");
        m.forward = b["forward"].asBool();
    }
    // A path without a class is the forward pass's only: a material on it that the G-buffer pass
    // could draw would have no lighting pass (black).
    if (!m.path.empty() && m.stencil.empty() && !m.forward)
        return w.at("path").error("lighting path '" + m.path +
                                  "' has no stencil class (it is the forward pass's only): give "
                                  "the material forward = true, or the path a stencil class");
    m.fixup = b["fixup"].asString();
    if (!m.fixup.empty()) {
        auto p = resolvePass(w.at("fixup"), d.module, m.fixup);
        if (!p) return std::unexpected(p.error());
        m.fixup = *p;
    }
    if (!m.fills.empty() && m.fills.size() < lit->targets.size() && m.fixup.empty())
        return w.at("fixup").error("material fills only part of layout '" + m.layout +
                                   "': name the fix-up pass that fills the rest");
    if (auto r = standardChannels(w, b, *lit, m); !r) return r;
    // A lighting path's pass and shading function decode one layout.
    if (!m.path.empty())
        for (const MaterialDesc& other : out.materials)
            if (other.path == m.path && other.layout != m.layout)
                return w.at("path").error("lighting path '" + m.path + "' lights layout '" +
                                          other.layout + "' (material '" + other.name + "', " +
                                          other.origin + "); this material's layout is '" +
                                          m.layout +
                                          "': a path's lighting pass and shading function decode "
                                          "one layout, so declare a path of its own");
    if (b.has("params"))
        if (auto r = expectType(w.at("params"), b["params"], "table"); !r) return r;
    m.params = b["params"];
    // Numeric params become `#define NAME material.custom[i][j]` in the generated G-buffer
    // shader (passes/scene_pass.cpp): a name that is also a layout channel, a field of the
    // sampled surface or a name of the generated code would rewrite that code.
    {
        static const std::vector<std::string> reserved = {
            "position",
            "normal",
            "baseColor",
            "opacity",
            "smoothness",
            "metalMask",
            "reflectance",
            "ao",
            "emissive",
            "diffuseColor",
            "f0",
            "twoColour",
            "radiosity",
            "tangentFrame",  // RgSurface (shaders/lib/material.glsl)
            "material",
            "s",
            "g",
            "main",
            "worldPosition",
            "worldNormal",
            "worldTangent",
            "uv0",
            "uv1"};  // the generated code
        // A parameter's or texture's name, checked where `pw` says.
        auto checkName = [&](const Where& pw, const std::string& name,
                             const char* what) -> Result<void> {
            if (!isGlslIdentifier(name))
                return pw.error(std::string("a material ") + what +
                                "'s name must be a GLSL identifier (letters, digits, _)");
            if (name.rfind("rg", 0) == 0 || name.rfind("RG_", 0) == 0 || name.rfind("gl_", 0) == 0)
                return pw.error(
                    "names starting with 'rg', 'RG_' or 'gl_' are rgraph's and GLSL's; choose "
                    "another");
            for (const auto& t : lit->targets)
                for (const auto& c : t.channels)
                    if (c.name == name)
                        return pw.error("clashes with channel '" + name + "' of layout '" +
                                        m.layout + "' (target " + t.name +
                                        "): the generated shader defines each parameter as a name; "
                                        "choose another");
            if (std::find(reserved.begin(), reserved.end(), name) != reserved.end())
                return pw.error("clashes with '" + name +
                                "' of the generated G-buffer shader (the sampled surface's fields "
                                "and its variables: " +
                                joinQuoted(reserved) + "); choose another");
            return {};
        };
        for (const auto& [name, value] : m.params.asTable())
            if (auto r = checkName(w.at("params").at(name), name, "parameter"); !r) return r;
        // Its own textures (at most kMaterialTextureSlots): `NAME(s)` in its surface function
        // samples one at the surface's uv (passes/scene_pass_glsl.cpp surfaceInclude).
        auto textures = stringList(w.at("textures"), b["textures"]);
        if (!textures) return std::unexpected(textures.error());
        if (textures->size() > kMaterialTextureSlots)
            return w.at("textures")
                .error("at most " + std::to_string(kMaterialTextureSlots) +
                       " textures a material, got " + std::to_string(textures->size()));
        for (size_t i = 0; i < textures->size(); ++i) {
            const std::string& name = (*textures)[i];
            if (auto r = checkName(w.at("textures").index(i), name, "texture"); !r) return r;
            if (!m.params[name].isNil() ||
                std::count(textures->begin(), textures->begin() + long(i), name))
                return w.at("textures")
                    .index(i)
                    .error("'" + name +
                           "' is already a parameter or texture of "
                           "this material; choose another");
        }
        m.textures = *textures;
        std::sort(m.textures.begin(), m.textures.end());
    }
    out.materials.push_back(m);
    return {};
}

// A pixel's material is its stencil value, its identity: the G-buffer pass writes it, and every
// pass that decodes the G-buffer (decals, debug views, the sun's mask, SSR, AO, the reference,
// captures) reads it as a stencil texture and unpacks the pixel with that material's layout
// (gbuffer_pipeline.glsl). A material takes its stencil class's value (the class of its path,
// or `stencil`) when that is free or held by a material that decodes alike (the same layout,
// channels and decals); otherwise, unless it named its stencil class, the next free variant of
// the class (the high bits: the class's lighting pass, testing the low bits, still lights it). A
// material without a class takes a value whose low bits are 0: no lighting pass lights it.
Result<void> Builder::materialIdentities() {
    const uint32_t bits = options.stencilBits;
    const uint32_t low = (1u << bits) - 1, variants = (1u << (8 - bits)) - 1;
    std::set<uint32_t> declared;  // the stencil classes' values, variants' included
    for (const StencilClassDesc& c : out.stencilClasses) declared.insert(c.value);
    std::map<uint32_t, const MaterialDesc*> held;
    auto alike = [](const MaterialDesc& a, const MaterialDesc& b) {
        return a.layout == b.layout && a.channels == b.channels && a.decals == b.decals;
    };
    // Materials that name their class first, so that their values do not depend on the order.
    for (int round = 0; round < 2; ++round)
        for (MaterialDesc& m : out.materials) {
            const Declaration& d = *std::find_if(decls.begin(), decls.end(), [&](auto& x) {
                return x.kind == DeclKind::Material && fullName(x) == m.name;
            });
            const bool named = d.body.has("stencil");
            if (named != (round == 0)) continue;
            auto cls = std::find_if(out.stencilClasses.begin(), out.stencilClasses.end(),
                                    [&](auto& c) { return c.name == m.stencil; });
            const uint32_t value = cls == out.stencilClasses.end() ? 0 : cls->value;
            std::vector<uint32_t> candidates;
            if (value != 0) candidates.push_back(value);
            if (!named)
                for (uint32_t k = 1; k <= variants; ++k) {
                    const uint32_t v = (value & low) | (k << bits);
                    if (!declared.count(v)) candidates.push_back(v);
                }
            auto pick = std::find_if(candidates.begin(), candidates.end(), [&](uint32_t v) {
                return !held.count(v) || alike(*held[v], m);
            });
            if (pick != candidates.end()) {
                m.identity = *pick;
                held.emplace(m.identity, &m);
                continue;
            }
            const std::string className =
                value ? "stencil class '" + m.stencil + "'" : std::string("no class");
            if (!candidates.empty() && named) {
                const MaterialDesc& other = *held[value];
                return where(d).at("stencil").error(
                    "its pixels would carry stencil value " + std::to_string(value) + " (" +
                    className + "), the identity of material '" + other.name + "' (" +
                    other.origin + "), which decodes otherwise (layout '" + other.layout +
                    "'): materials sharing a stencil value share their layout, channels and "
                    "decals; "
                    "give it a class of its own (rg.stencil \"...\" { variant_of = \"" +
                    m.stencil +
                    "\" } keeps the class's lighting) or leave out stencil to have a variant "
                    "chosen");
            }
            std::vector<std::string> holders;
            for (const auto& [v, h] : held)
                if ((v & low) == (value & low)) holders.push_back(h->name);
            return where(d).error("no material identity left for " + className + ": its " +
                                  std::to_string(candidates.size()) +
                                  " stencil values are held by materials " + joinQuoted(holders) +
                                  " and declared variants; declare a stencil class of its own");
        }
    return {};
}

// Passes that name stencil classes (stencil = { class = ... }) or select materials (scene
// passes: materials = { ... }, paths = { ... }) name ones that exist, with surfaces.
Result<void> Builder::checkMaterialReferences() {
    for (const auto& p : out.graph.passes) {
        const Declaration& d = *passes[p.name];
        Where w = where(d);
        const Value& stencil = p.params["stencil"];
        if (stencil.has("class")) {
            const std::string cls = stencil["class"].asString();
            if (!hasStencil(cls))
                return w.at("stencil").at("class").error("unknown stencil class '" + cls + "'" +
                                                         suggestion(cls, stencilNames()));
        }
        if (p.kind != "scene") continue;
        std::vector<std::string> materialNames, pathNames;
        for (const auto& m : out.materials) materialNames.push_back(m.name);
        for (const auto& lp : out.lightingPaths) pathNames.push_back(lp.name);
        auto selected = stringList(w.at("materials"), p.params["materials"]);
        if (!selected) return std::unexpected(selected.error());
        for (size_t i = 0; i < selected->size(); ++i)
            if (std::find(materialNames.begin(), materialNames.end(), (*selected)[i]) ==
                materialNames.end())
                return w.at("materials")
                    .index(i)
                    .error("unknown material '" + (*selected)[i] + "'" +
                           suggestion((*selected)[i], materialNames));
        auto paths = stringList(w.at("paths"), p.params["paths"]);
        if (!paths) return std::unexpected(paths.error());
        for (size_t i = 0; i < paths->size(); ++i)
            if (std::find(pathNames.begin(), pathNames.end(), (*paths)[i]) == pathNames.end())
                return w.at("paths").index(i).error("unknown lighting path '" + (*paths)[i] + "'" +
                                                    suggestion((*paths)[i], pathNames));
        for (const auto& m : out.materials) {
            const bool chosen =
                (selected->empty() && paths->empty()) ||
                std::find(selected->begin(), selected->end(), m.name) != selected->end() ||
                std::find(paths->begin(), paths->end(), m.path) != paths->end();
            if (chosen && m.surface.empty())
                return w.error("material '" + m.name + "' (" + m.origin +
                               ") has no surface function (surface = \"file.glsl\"), so this scene "
                               "pass cannot draw it");
        }
    }
    return {};
}

}  // namespace rg::declarations

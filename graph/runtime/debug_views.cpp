// The debug views that --view (SessionOptions::view) adds after the pipeline's passes: a fullscreen
// decode of a G-buffer channel, the stencil classes, the shadow cascades, the lightmap's lobes.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>

#include "core/names.h"
#include "passes/passes.h"
#include "session_detail.h"

namespace rg {

namespace {

const std::vector<std::string> kViews = {"normals",    "basecolor",   "smoothness", "metalmask",
                                         "materialid", "reflectance", "ao",         "emissive"};

// The debug view's fullscreen pass: `reads`, then the view target it writes; `params` its shader
// and uniforms.
void addViewPass(GraphDesc& g, std::vector<Access> reads, Value::Table params) {
    PassDesc pass;
    pass.name = "debug_view";
    pass.kind = "fullscreen";
    pass.accesses = std::move(reads);
    pass.accesses.push_back({"debug_view", Usage::ColorAttachment});
    pass.params = Value(std::move(params));
    g.passes.push_back(std::move(pass));
}

// A view that needs `resource`: an error naming what provides it when the pipeline lacks it.
Result<void> needs(const GraphDesc& g, const std::string& view, const std::string& resource,
                   const std::string& hint) {
    if (g.findResource(resource)) return {};
    return fail(ErrorCode::InvalidInput,
                "--view " + view + ": the pipeline has no '" + resource + "' (" + hint + ")");
}

}  // namespace

namespace detail {

// Appends the debug view's passes: a fullscreen decode of the disney G-buffer, or for the
// stencil one colour per stencil class drawn with that class's stencil test.
Result<void> addDebugView(GraphDesc& g, const PipelineDesc& p, const std::string& view,
                          const Scene* scene) {
    for (const char* r : {"GB0", "GB1", "GB2", "GB3", "depth"})
        if (!g.findResource(r))
            return fail(ErrorCode::InvalidInput,
                        "--view " + view + ": the pipeline has no '" + r +
                            "' (views read the disney G-buffer GB0..GB3 and depth)");
    ResourceDesc out;
    out.name = "debug_view";
    out.texture.format = Format::RGBA8Unorm;
    out.exported = true;
    g.resources.push_back(out);
    // shadow:LIGHT — that local light's shadow maps this frame (a spot's one, a cube's six).
    if (view.starts_with("shadow:")) {
        const std::string name = view.substr(7);
        if (auto r = needs(g, view, "local_shadow", "require \"shadows\""); !r) return r;
        std::string shadowed;
        int index = -1;
        for (size_t i = 0; scene && i < scene->lights.size(); ++i) {
            const Light& l = scene->lights[i];
            if (!l.castShadows) continue;
            shadowed += (shadowed.empty() ? "'" : ", '") + l.name + "'";
            if (l.name == name) index = static_cast<int>(i);
        }
        if (index < 0)
            return fail(
                ErrorCode::InvalidInput,
                "--view " + view + ": the scene has no light '" + name + "' that casts shadows (" +
                    (shadowed.empty() ? std::string("none does: give a local light shadow = true")
                                      : "those that do: " + shadowed) +
                    ")");
        addViewPass(
            g, {{"local_shadow", Usage::Sampled}},
            {{"shader", Value("passes/local_shadow_view.frag")},
             {"uniforms", Value(Value::Table{{"light", Value(static_cast<double>(index))}})}});
        return {};
    }
    if (view == "stencil") {
        PassDesc clear;
        clear.name = "debug_view_clear";
        clear.kind = "clear";
        clear.type = PassType::Transfer;
        clear.accesses = {{"debug_view", Usage::CopyDst}};
        clear.params = Value(Value::Table{{"value", Value(Value::List{0.0, 0.0, 0.0, 1.0})}});
        g.passes.push_back(clear);
        static const double colors[][3] = {{0.9, 0.2, 0.2}, {0.2, 0.8, 0.2}, {0.2, 0.4, 0.9},
                                           {0.9, 0.8, 0.2}, {0.8, 0.3, 0.9}, {0.2, 0.9, 0.9},
                                           {0.9, 0.5, 0.1}, {0.6, 0.6, 0.6}};
        for (size_t i = 0; i < p.stencilClasses.size(); ++i) {
            const auto& c = p.stencilClasses[i];
            PassDesc pass;
            pass.name = "debug_view_" + c.name;
            pass.kind = "fullscreen";
            pass.accesses = {{"depth", Usage::DepthStencilRead},
                             {"debug_view", Usage::ColorAttachment, /*load=*/true}};
            const double* rgb = colors[i % 8];
            pass.params = Value(Value::Table{
                {"shader", Value("passes/stencil_view.frag")},
                {"stencil", Value(Value::Table{{"ref", Value(static_cast<double>(c.value))},
                                               {"mask", Value(255.0)},
                                               {"compare", Value("equal")}})},
                {"uniforms",
                 Value(Value::Table{
                     {"class_color", Value(Value::List{rgb[0], rgb[1], rgb[2], 1.0})}})}});
            g.passes.push_back(pass);
        }
        return {};
    }
    if (view == "lights") {
        if (auto r = needs(g, view, "light_tiles",
                           "require \"lighting\" and light its passes with lighting.tiled");
            !r)
            return r;
        addViewPass(g, {{"light_tiles", Usage::StorageRead}, {"depth", Usage::Sampled}},
                    {{"shader", Value("passes/light_count_view.frag")},
                     {"defines", Value(Value::Table{{"RG_LIGHT_TILES", Value(true)}})}});
        return {};
    }
    if (view == "ssr" || view == "ssr_confidence") {
        if (auto r = needs(g, view, "ssr", "require \"ssr\""); !r) return r;
        if (auto r = needs(g, view, "exposure", "post.exposure_state(): the reflection is in nits");
            !r)
            return r;
        addViewPass(
            g, {{"ssr", Usage::Sampled}, {"exposure", Usage::StorageRead}},
            {{"shader", Value("passes/ssr_view.frag")},
             {"uniforms", Value(Value::Table{{"view", Value(view == "ssr" ? 0.0 : 1.0)}})}});
        return {};
    }
    if (view == "reflection") {
        if (auto r = needs(g, view, "reflection", "require \"reflections\""); !r) return r;
        if (auto r = needs(g, view, "exposure", "post.exposure_state(): the reflection is in nits");
            !r)
            return r;
        addViewPass(g, {{"reflection", Usage::Sampled}, {"exposure", Usage::StorageRead}},
                    {{"shader", Value("passes/ssr_view.frag")},
                     {"bind", Value(Value::Table{{"ssr", Value("reflection")}})},
                     {"uniforms", Value(Value::Table{{"view", Value(2.0)}})}});
        return {};
    }
    if (view == "probes") {
        addViewPass(g, {{"depth", Usage::Sampled}}, {{"shader", Value("passes/probe_view.frag")}});
        return {};
    }
    if (view == "ssao") {
        if (auto r = needs(g, view, "ssao", "require \"ao\""); !r) return r;
        addViewPass(g, {{"ssao", Usage::Sampled}}, {{"shader", Value("passes/ssao_view.frag")}});
        return {};
    }
    if (view == "cascades" || view == "shadow") {
        for (const char* r : {"sun_shadow0", "sun_cascades"})
            if (auto n = needs(g, view, r, "require \"shadows\""); !n) return n;
        // The maps, one per cascade (scripts/shadows.lua): sun_shadow0 ..
        std::vector<Access> maps;
        while (maps.size() < 4 && g.findResource("sun_shadow" + std::to_string(maps.size())))
            maps.push_back({"sun_shadow" + std::to_string(maps.size()), Usage::Sampled});
        Value::Table defines{{"RG_SUN_CASCADES", Value(static_cast<double>(maps.size()))}};
        if (view == "shadow") {
            addViewPass(
                g, maps,
                {{"shader", Value("passes/shadow_map_view.frag")}, {"defines", Value(defines)}});
        } else {
            std::vector<Access> reads{{"GB0", Usage::Sampled},
                                      {"depth", Usage::Sampled},
                                      {"sun_cascades", Usage::UniformRead}};
            reads.insert(reads.end(), maps.begin(), maps.end());
            addViewPass(
                g, reads,
                {{"shader", Value("passes/cascade_view.frag")}, {"defines", Value(defines)}});
        }
        return {};
    }
    // lightmap / sgN: the G-buffer pass writes the baked lightmap — the irradiance at the shaded
    // normal, or lobe N's amplitude — as the emission (RG_LIGHTMAP_VIEW), shown in colour.
    if (view == "lightmap" || (view.size() > 2 && view.starts_with("sg") &&
                               view.find_first_not_of("0123456789", 2) == std::string::npos)) {
        const Lightmap* lm = scene ? scene->bakedLightmap.get() : nullptr;
        if (!lm)
            return fail(
                ErrorCode::InvalidInput,
                "--view " + view +
                    ": the scene has no baked lightmap (declare scene.lightmap; the pipeline's "
                    "lightmap parameter must be on)");
        int what = 0;
        if (view != "lightmap") {
            const int lobe = std::atoi(view.c_str() + 2);
            if (lobe < 0 || size_t(lobe) >= lm->axes.size())
                return fail(ErrorCode::InvalidInput, "--view " + view +
                                                         ": the lightmap has lobes sg0 .. sg" +
                                                         std::to_string(lm->axes.size() - 1));
            what = lobe + 1;
        }
        bool found = false;
        for (PassDesc& pass : g.passes)
            if (pass.name == "gbuffer") {
                Value::Table params =
                    pass.params.isTable() ? pass.params.asTable() : Value::Table{};
                Value::Table defines =
                    params["defines"].isTable() ? params["defines"].asTable() : Value::Table{};
                defines["RG_LIGHTMAP_VIEW"] = Value(static_cast<double>(what + 1));
                params["defines"] = Value(defines);
                pass.params = Value(params);
                found = true;
            }
        if (!found)
            return fail(ErrorCode::InvalidInput,
                        "--view " + view + ": the pipeline has no 'gbuffer' scene pass");
        addViewPass(g,
                    {{"GB0", Usage::Sampled},
                     {"GB1", Usage::Sampled},
                     {"GB2", Usage::Sampled},
                     {"GB3", Usage::Sampled},
                     {"depth", Usage::Sampled}},
                    {{"shader", Value("passes/debug_view.frag")},
                     {"uniforms", Value(Value::Table{{"view", Value(8.0)}})}});
        return {};
    }
    auto it = std::find(kViews.begin(), kViews.end(), view);
    if (it == kViews.end()) {
        std::string all =
            "'stencil', 'lights', 'ssao', 'ssr', 'ssr_confidence', 'reflection', 'probes', "
            "'cascades', 'shadow', 'shadow:LIGHT', "
            "'lightmap', 'sgN'";
        for (const auto& v : kViews) all += ", '" + v + "'";
        return fail(ErrorCode::InvalidInput,
                    "--view: unknown view '" + view + "'; expected one of: " + all);
    }
    Value::Table params{
        {"shader", Value("passes/debug_view.frag")},
        {"uniforms",
         Value(Value::Table{{"view", Value(static_cast<double>(it - kViews.begin()))}})}};
    addViewPass(g,
                {{"GB0", Usage::Sampled},
                 {"GB1", Usage::Sampled},
                 {"GB2", Usage::Sampled},
                 {"GB3", Usage::Sampled},
                 {"depth", Usage::Sampled}},
                std::move(params));
    return {};
}

}  // namespace detail

}  // namespace rg

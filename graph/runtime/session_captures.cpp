// Session's captures of G-buffer channels ("gbuffer.<channel>", "<layout>.<channel>"): the
// names checked against the pipeline's layouts, and each pixel's channel decoded on the CPU with
// the layout of its material, which the G-buffer's stencil names (MaterialDesc::identity).
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
#include "layout/layout.h"
#include "session_detail.h"

namespace rg {

// One `--capture gbuffer.X` / `LAYOUT.X` as an image: each pixel decoded on the CPU with its
// material's layout (by its identity, the stencil value), NaN where that material has no such
// channel.
Result<Image> Session::channelImage(const ChannelCapture& ch) const {
    auto info = analyzeLayout(ch.layout);
    if (!info) return std::unexpected(info.error());
    std::vector<Image> targets;
    for (const auto& t : ch.layout.targets) {
        auto img = m_runtime.executor().readback(t.name);
        if (!img) return std::unexpected(img.error());
        targets.push_back(std::move(*img));
    }
    // Each pixel decoded with its material's layout (by its stencil), else with ch.layout.
    struct Decoder {
        LayoutInfo info;
        std::vector<Image*> targets;
        int index = -1;
    };
    std::map<std::string, Image> extra;  // targets the id layout does not have
    auto decoderFor = [&](const LayoutDesc& l, const std::string& channel) -> Result<Decoder> {
        auto li = analyzeLayout(l);
        if (!li) return std::unexpected(li.error());
        Decoder d{*li, {}, li->find(channel)};
        for (const auto& t : l.targets) {
            auto it = std::find_if(ch.layout.targets.begin(), ch.layout.targets.end(),
                                   [&](auto& x) { return x.name == t.name; });
            if (it != ch.layout.targets.end()) {
                d.targets.push_back(&targets[static_cast<size_t>(it - ch.layout.targets.begin())]);
                continue;
            }
            if (!extra.count(t.name)) {
                auto img = m_runtime.executor().readback(t.name);
                if (!img) return std::unexpected(img.error());
                extra[t.name] = std::move(*img);
            }
            d.targets.push_back(&extra[t.name]);
        }
        return d;
    };
    auto main = decoderFor(ch.layout, ch.channel);
    if (!main) return std::unexpected(main.error());
    std::map<uint32_t, Decoder> byId;
    for (const auto& [id, lc] : ch.byId) {
        auto d = decoderFor(lc.first, lc.second);
        if (!d) return std::unexpected(d.error());
        byId.emplace(id, std::move(*d));
    }
    Image identities;
    if (!byId.empty() && !ch.stencil.empty()) {
        auto img = m_runtime.executor().readback(ch.stencil, 0, 0, true);
        if (!img) return std::unexpected(img.error());
        identities = std::move(*img);
    }
    const ChannelDesc& desc = main->index >= 0
                                  ? main->info.channelDesc(static_cast<size_t>(main->index))
                                  : byId.begin()->second.info.channelDesc(
                                        static_cast<size_t>(byId.begin()->second.index));
    const bool integer = desc.encoding == Encoding::Uint;
    const uint32_t comps = valueComponents(desc);
    Image out(targets[0].width, targets[0].height, comps);
    auto decode = [&](const Decoder& d, uint32_t x, uint32_t y) {
        std::vector<TexelValue> texels(d.targets.size());
        for (size_t t = 0; t < d.targets.size(); ++t)
            texels[t] = texelFromFloats(
                d.info.desc.targets[t].format,
                &d.targets[t]->pixels[(size_t(y) * out.width + x) * d.targets[t]->channels],
                d.targets[t]->channels);
        return unpackTexel(d.info, texels);
    };
    const float nan = std::numeric_limits<float>::quiet_NaN();
    for (uint32_t y = 0; y < out.height; ++y)
        for (uint32_t x = 0; x < out.width; ++x) {
            const Decoder* d = &*main;
            if (!identities.pixels.empty()) {
                auto it = byId.find(static_cast<uint32_t>(identities.at(x, y, 0)));
                d = it == byId.end() ? nullptr : &it->second;
            }
            if (!d || d->index < 0) {
                for (uint32_t c = 0; c < comps; ++c)
                    out.at(x, y, c) = nan;  // its material has no such channel
                continue;
            }
            auto values = decode(*d, x, y);
            const ChannelValue& v = values[static_cast<size_t>(d->index)];
            for (uint32_t c = 0; c < comps; ++c)
                out.at(x, y, c) = integer ? static_cast<float>(v.u[c]) : v.v[c];
        }
    return out;
}

// `--capture` names (and the library's keep, serve's image requests) checked against a pipeline:
// a resource of its graph, or "gbuffer.<channel>" / "<layout>.<channel>", decoded per material.
Result<std::vector<Session::ChannelCapture>> detail::channelCapturesOf(
    const PipelineDesc& pipeline, const std::vector<std::string>& captures) {
    using ChannelCapture = Session::ChannelCapture;
    std::vector<ChannelCapture> channels;
    for (const auto& c : captures) {
        if (pipeline.graph.findResource(c)) continue;
        // "gbuffer.smoothness" or "disney.smoothness": a channel of a layout.
        const size_t dot = c.find('.');
        bool found = false;
        if (dot != std::string::npos) {
            const std::string prefix = c.substr(0, dot), channel = c.substr(dot + 1);
            auto has = [](const LayoutDesc& l, const std::string& name) {
                for (const auto& t : l.targets)
                    for (const auto& ch : t.channels)
                        if (ch.name == name) return true;
                return false;
            };
            for (const auto& l : pipeline.layouts) {
                if (prefix != "gbuffer" && prefix != l.name) continue;
                if (has(l, channel) && !found) {
                    channels.push_back({c, l, channel, {}});
                    found = true;
                }
            }
            // Per identity: the material's own layout, and its channel for a standard name.
            for (const MaterialDesc& m : pipeline.materials) {
                const LayoutDesc& l =
                    *std::find_if(pipeline.layouts.begin(), pipeline.layouts.end(),
                                  [&](auto& x) { return x.name == m.layout; });
                if (prefix != "gbuffer" && prefix != l.name) continue;
                const auto mapped = m.channels.find(channel);
                const std::string name =
                    prefix == "gbuffer" && mapped != m.channels.end() ? mapped->second : channel;
                if (!has(l, name)) continue;
                if (!found) {
                    channels.push_back({c, l, name, {}});
                    found = true;
                }
                // Only channels of the same shape as the first (components, integer or not); the
                // others' pixels stay NaN.
                auto shape = [](const LayoutDesc& ld, const std::string& ch) {
                    for (const auto& t : ld.targets)
                        for (const auto& cd : t.channels)
                            if (cd.name == ch) {
                                return std::make_pair(valueComponents(cd),
                                                      cd.encoding == Encoding::Uint);
                            }
                    return std::make_pair(0u, false);
                };
                const auto& first =
                    channels.back().byId.empty()
                        ? std::make_pair(channels.back().layout, channels.back().channel)
                        : channels.back().byId.begin()->second;
                if (shape(l, name) == shape(first.first, first.second))
                    channels.back().byId.emplace(m.identity, std::make_pair(l, name));
            }
            // The identities: the stencil of the depth the G-buffer pass (a scene pass drawing
            // materials into the layouts' targets) writes.
            if (found && !channels.back().byId.empty())
                for (const PassDesc& pass : pipeline.graph.passes) {
                    if (pass.kind != "scene" || pass.params["forward"].asBool() ||
                        pass.params["shadow"].asBool() || pass.params["capture"].asBool())
                        continue;
                    for (const Access& a : pass.accesses)
                        if (a.usage == Usage::DepthStencilAttachment)
                            if (const ResourceDesc* r = pipeline.graph.findResource(a.resource);
                                r && r->kind == ResourceKind::Texture &&
                                formatInfo(r->texture.format).stencil &&
                                channels.back().stencil.empty())
                                channels.back().stencil = a.resource;
                }
        }
        if (!found)
            return fail(ErrorCode::NotFound,
                        "capture '" + c + "': the pipeline has no resource named '" + c +
                            "' (nor a G-buffer channel: use gbuffer.<channel>)");
    }
    return channels;
}

}  // namespace rg

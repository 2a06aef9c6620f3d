// rg.layout: a G-buffer layout's targets and their channels ("name:encoding:bits"), checked by
// analyzeLayout.
#include "declarations_detail.h"

#include <cctype>
#include <vector>

namespace rg::declarations {

Result<void> Builder::layout(const Declaration& d) {
    Where w = where(d);
    LayoutDesc l;
    // Layout names become GLSL identifiers (GBuffer_<name>): modules use '_' as separator.
    l.name = d.module.empty() ? d.name : d.module + "_" + d.name;
    l.origin = d.origin;
    if (!d.body.isList())
        return w.error(
            "expected a list of targets: { { \"GB0\", \"rgb10a2\", { \"normal:oct:20\", ... } }, "
            "... }");
    for (size_t i = 0; i < d.body.asList().size(); ++i) {
        const Value& t = d.body.asList()[i];
        Where tw = w.index(i);
        if (!t.isList() || t.asList().size() != 3 || !t.asList()[0].isString() ||
            !t.asList()[1].isString() || !t.asList()[2].isList())
            return tw.error(
                "expected { \"name\", \"format\", { \"channel:encoding:bits\", ... } }");
        TargetDesc target;
        target.name = t.asList()[0].asString();
        target.origin = d.origin;
        auto f = parseFormat(t.asList()[1].asString());
        if (!f)
            return tw.index(1).error("unknown format '" + t.asList()[1].asString() +
                                     "'; expected one of: " + formatNameList());
        target.format = *f;
        const auto& channels = t.asList()[2].asList();
        for (size_t c = 0; c < channels.size(); ++c) {
            Where cw = tw.index(2).index(c);
            if (!channels[c].isString())
                return cw.error("expected \"name:encoding:bits\", got " + typeOf(channels[c]));
            std::string spec = channels[c].asString();
            std::vector<std::string> parts;
            size_t start = 0;
            for (size_t pos; (pos = spec.find(':', start)) != std::string::npos; start = pos + 1)
                parts.push_back(spec.substr(start, pos - start));
            parts.push_back(spec.substr(start));
            // bits: a total ("20") or per component times components ("16x3").
            uint32_t components = 0, bits = 0;
            bool ok = parts.size() == 3 && !parts[0].empty();
            if (ok) {
                std::string b = parts[2];
                size_t x = b.find('x');
                std::string total = x == std::string::npos ? b : b.substr(0, x);
                std::string count = x == std::string::npos ? "" : b.substr(x + 1);
                ok = !total.empty() && total.size() <= 3 &&
                     total.find_first_not_of("0123456789") == std::string::npos &&
                     (x == std::string::npos ||
                      (!count.empty() && count.size() == 1 &&
                       std::isdigit(static_cast<unsigned char>(count[0]))));
                if (ok) {
                    bits = static_cast<uint32_t>(std::stoul(total));
                    if (!count.empty()) {
                        components = static_cast<uint32_t>(count[0] - '0');
                        bits *= components;
                    }
                }
            }
            if (!ok)
                return cw.error(
                    "expected \"name:encoding:bits\" (e.g. \"smoothness:unorm:10\" or "
                    "\"emissive:float:16x3\"), got \"" +
                    spec + "\"");
            ChannelDesc ch;
            ch.name = parts[0];
            ch.origin = d.origin;
            auto encoding = parseEncoding(parts[1]);
            if (!encoding) {
                std::vector<std::string> names;
                for (auto e : {Encoding::Unorm, Encoding::Snorm, Encoding::Srgb, Encoding::Oct,
                               Encoding::Uint, Encoding::Float})
                    names.emplace_back(encodingName(e));
                return cw.error("unknown encoding '" + parts[1] + "'" +
                                suggestion(parts[1], names) +
                                "; expected one of: " + encodingNameList());
            }
            ch.encoding = *encoding;
            ch.bits = bits;
            ch.components = components;
            target.channels.push_back(ch);
        }
        l.targets.push_back(target);
    }
    auto info = analyzeLayout(l);
    if (!info) return std::unexpected(info.error());
    out.layouts.push_back(l);
    return {};
}

}  // namespace rg::declarations

// Fuzz target: G-buffer layout analysis and code generation (graph/layout): the input's bytes
// describe a layout — up to 4 targets of any colour format, up to 6 channels each of any encoding,
// bit count and component count, names from a small set (so collisions happen) — which
// analyzeLayout validates; for a valid one the GLSL is generated and a texel of bytes from the
// input packed and unpacked through the C++ twin of that GLSL.
#include <array>
#include <vector>

#include "fuzz_common.h"
#include "layout/layout.h"

namespace {

struct Bytes {
    const uint8_t* data;
    size_t size, at = 0;
    uint8_t next() { return at < size ? data[at++] : 0; }
    float unit() { return static_cast<float>(next()) / 255.0f; }
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    static const std::array<const char*, 8> names = {
        "normal", "baseColor", "smoothness", "materialId", "ao", "emissive", "x", "normal"};
    Bytes in{data, size};
    rg::LayoutDesc desc;
    desc.name = (in.next() & 1) ? "fuzz" : "disney";
    const int targets = 1 + in.next() % 4;
    for (int t = 0; t < targets; ++t) {
        rg::TargetDesc target;
        target.name = "GB" + std::to_string(t);
        target.format =
            static_cast<rg::Format>(in.next() % static_cast<uint8_t>(rg::Format::Count));
        const int channels = in.next() % 7;
        for (int c = 0; c < channels; ++c) {
            rg::ChannelDesc ch;
            ch.name = names[in.next() % names.size()];
            ch.encoding = static_cast<rg::Encoding>(in.next() % 6);
            ch.bits = in.next() % 70;
            ch.components = in.next() % 6;
            target.channels.push_back(ch);
        }
        desc.targets.push_back(target);
    }
    auto info = rg::analyzeLayout(desc);
    if (!info) return 0;
    const std::string glsl = rg::generateGlsl(*info);
    if (glsl.empty()) std::abort();
    std::vector<rg::ChannelValue> values(info->channels.size());
    for (auto& v : values)
        for (int k = 0; k < 4; ++k) {
            v.v[static_cast<size_t>(k)] = in.unit() * 2.0f - 0.5f;
            v.u[static_cast<size_t>(k)] = in.next() * 0x01010101u;
        }
    const auto texels = rg::packTexel(*info, values);
    if (texels.size() != info->desc.targets.size()) std::abort();
    (void)rg::unpackTexel(*info, texels);
    return 0;
}

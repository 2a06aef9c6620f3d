#include "format.h"

#include <array>

namespace rg {

namespace {

// name, bytes, components, depth, stencil, srgb, integer, floating
constexpr std::array<FormatInfo, static_cast<size_t>(Format::Count)> kFormats{{
    {Format::Undefined, "undefined", 0, 0, false, false, false, false, false},
    {Format::R8Unorm, "r8", 1, 1, false, false, false, false, false},
    {Format::RG8Unorm, "rg8", 2, 2, false, false, false, false, false},
    {Format::RGBA8Unorm, "rgba8", 4, 4, false, false, false, false, false},
    {Format::RGBA8Srgb, "rgba8_srgb", 4, 4, false, false, true, false, false},
    {Format::RGB10A2Unorm, "rgb10a2", 4, 4, false, false, false, false, false},
    {Format::R11G11B10F, "r11g11b10f", 4, 3, false, false, false, false, true},
    {Format::R16F, "r16f", 2, 1, false, false, false, false, true},
    {Format::RG16F, "rg16f", 4, 2, false, false, false, false, true},
    {Format::RGBA16F, "rgba16f", 8, 4, false, false, false, false, true},
    {Format::R32F, "r32f", 4, 1, false, false, false, false, true},
    {Format::RG32F, "rg32f", 8, 2, false, false, false, false, true},
    {Format::RGBA32F, "rgba32f", 16, 4, false, false, false, false, true},
    {Format::R8Uint, "r8ui", 1, 1, false, false, false, true, false},
    {Format::R32Uint, "r32ui", 4, 1, false, false, false, true, false},
    {Format::RGBA32Uint, "rgba32ui", 16, 4, false, false, false, true, false},
    {Format::D16, "d16", 2, 1, true, false, false, false, false},
    {Format::D32F, "d32f", 4, 1, true, false, false, false, true},
    {Format::D24S8, "d24_s8", 4, 2, true, true, false, false, false},
    {Format::D32FS8, "d32f_s8", 8, 2, true, true, false, false, true},
}};

}  // namespace

const FormatInfo& formatInfo(Format f) { return kFormats[static_cast<size_t>(f)]; }

std::optional<Format> parseFormat(std::string_view name) {
    for (const auto& info : kFormats)
        if (info.format != Format::Undefined && name == info.name) return info.format;
    return std::nullopt;
}

std::string formatNameList() {
    std::string s;
    for (const auto& info : kFormats) {
        if (info.format == Format::Undefined) continue;
        if (!s.empty()) s += ", ";
        s += "'";
        s += info.name;
        s += "'";
    }
    return s;
}

}  // namespace rg

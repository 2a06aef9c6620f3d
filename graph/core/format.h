// Texel formats as the graph and the scripts name them. Vulkan-free: the GPU layer maps each
// Format to its VkFormat. Names ("rgba16f", "d32f_s8", ...) are the ones Lua scripts use.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace rg {

enum class Format : uint8_t {
    Undefined,
    R8Unorm,
    RG8Unorm,
    RGBA8Unorm,
    RGBA8Srgb,
    RGB10A2Unorm,
    R11G11B10F,
    R16F,
    RG16F,
    RGBA16F,
    R32F,
    RG32F,
    RGBA32F,
    R8Uint,
    R32Uint,
    RGBA32Uint,
    D16,
    D32F,
    D24S8,
    D32FS8,
    Count
};

struct FormatInfo {
    Format format;
    const char* name;        // script name, e.g. "rgba16f"
    uint32_t bytesPerTexel;  // 0 for Undefined
    uint32_t components;
    bool depth;
    bool stencil;
    bool srgb;
    bool integer;   // unsigned integer channels (no filtering, no blending)
    bool floating;  // float channels (half or single)
};

const FormatInfo& formatInfo(Format f);
inline std::string_view formatName(Format f) { return formatInfo(f).name; }
// Parses a script name; nullopt when unknown.
std::optional<Format> parseFormat(std::string_view name);
// Comma-separated list of every script name, for error messages.
std::string formatNameList();

inline bool isDepthStencil(Format f) { return formatInfo(f).depth || formatInfo(f).stencil; }

}  // namespace rg

// What the graph compiler tests (tests/unit/test_compiler.cpp, test_compiler_plan.cpp) share:
// builders of resources, accesses and passes, compiling a graph that must compile, pass order.
#pragma once

#include <gtest/gtest.h>

#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

#include "core/compiler.h"

namespace rg::test {

inline ResourceDesc texture(const std::string& name, Format format = Format::RGBA8Unorm,
                            float scale = 1.0f) {
    ResourceDesc r;
    r.name = name;
    r.texture.format = format;
    r.texture.scaleX = r.texture.scaleY = scale;
    return r;
}

inline ResourceDesc absolute(const std::string& name, Format format, uint32_t w, uint32_t h) {
    ResourceDesc r = texture(name, format);
    r.texture.sizeMode = SizeMode::Absolute;
    r.texture.width = w;
    r.texture.height = h;
    return r;
}

inline ResourceDesc buffer(const std::string& name, uint64_t size) {
    ResourceDesc r;
    r.name = name;
    r.kind = ResourceKind::Buffer;
    r.buffer.size = size;
    return r;
}

inline ResourceDesc exported(ResourceDesc r) {
    r.exported = true;
    return r;
}

inline ResourceDesc imported(ResourceDesc r) {
    r.imported = true;
    return r;
}

inline Access use(const std::string& resource, Usage usage, bool load = false) {
    Access a;
    a.resource = resource;
    a.usage = usage;
    a.load = load;
    return a;
}
inline Access sampled(const std::string& r) { return use(r, Usage::Sampled); }
inline Access color(const std::string& r, bool load = false) {
    return use(r, Usage::ColorAttachment, load);
}
inline Access depth(const std::string& r, bool load = false) {
    return use(r, Usage::DepthStencilAttachment, load);
}
inline Access storageWrite(const std::string& r) { return use(r, Usage::StorageWrite); }

inline PassDesc pass(const std::string& name, PassType type,
                     std::initializer_list<Access> accesses) {
    PassDesc p;
    p.name = name;
    p.kind = type == PassType::Compute    ? "compute"
             : type == PassType::Transfer ? "copy"
                                          : "fullscreen";
    p.type = type;
    p.accesses = accesses;
    return p;
}
inline PassDesc raster(const std::string& name, std::initializer_list<Access> accesses) {
    return pass(name, PassType::Raster, accesses);
}
inline PassDesc compute(const std::string& name, std::initializer_list<Access> accesses) {
    return pass(name, PassType::Compute, accesses);
}

inline CompileOptions defaults() { return CompileOptions{}; }

inline Plan compileOk(const GraphDesc& g, const CompileOptions& o = defaults()) {
    auto plan = compile(g, o);
    EXPECT_TRUE(plan.has_value()) << (plan ? "" : plan.error().describe());
    return plan ? std::move(*plan) : Plan{};
}

inline std::vector<std::string> passOrder(const Plan& p) {
    std::vector<std::string> names;
    for (const auto& pass : p.passes) names.push_back(pass.name);
    return names;
}

}  // namespace rg::test

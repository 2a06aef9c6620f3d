// The fixture every GPU test suite shares: one Runtime per suite with the Vulkan validation layer
// on, and a check after each test that the layer said nothing during it.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <unistd.h>

#include "runtime/runtime.h"
#include "runtime/session.h"
#include "image/image.h"

namespace rg {

// How two renders of one view differ in green (the channel the eye weighs most): the mean
// |difference| relative to the mean of `b`, and the share of pixels off by more than 5 %.
struct RenderDifference {
    double mean = 0.0, share = 0.0;
};
inline RenderDifference greenDifference(const Image& a, const Image& b) {
    size_t off = 0;
    double diff = 0.0, sum = 0.0;
    for (size_t i = 0; i + 1 < a.pixels.size() && i + 1 < b.pixels.size(); i += a.channels) {
        const float x = a.pixels[i + 1], y = b.pixels[i + 1];
        off += std::abs(x - y) > 0.05f * std::max({x, y, 1e-3f});
        diff += std::abs(x - y);
        sum += y;
    }
    return {sum > 0 ? diff / sum : 1.0, double(off) / double(a.pixels.size() / a.channels)};
}

// A fresh folder outside the repository (a game team's package folder), removed afterwards.
struct TempFolder {
    std::filesystem::path dir;
    explicit TempFolder(const std::string& name)
        : dir(std::filesystem::temp_directory_path() /
              ("rgraph_" + name + "_" + std::to_string(::getpid()))) {
        std::filesystem::remove_all(dir);
        std::filesystem::create_directories(dir);
    }
    ~TempFolder() {
        std::error_code ec;
        std::filesystem::remove_all(dir, ec);
    }
};

// A scene camera's view-projection at width x height, as passes/gpu_scene.cpp builds it (near
// 0.05 m, far 1000 m, y down), and the pixel a world point lands on through it.
inline glm::mat4 cameraViewProj(glm::vec3 eye, glm::vec3 target, float fovDegrees, uint32_t width,
                                uint32_t height) {
    glm::mat4 proj = glm::perspectiveRH_ZO(glm::radians(fovDegrees), float(width) / float(height),
                                           0.05f, 1000.0f);
    proj[1][1] *= -1.0f;
    return proj * glm::lookAt(eye, target, glm::vec3(0, 1, 0));
}
inline glm::ivec2 pixelOf(const glm::mat4& viewProj, uint32_t width, uint32_t height, glm::vec3 p) {
    glm::vec4 c = viewProj * glm::vec4(p, 1.0f);
    glm::vec2 uv = glm::vec2(c) / c.w * 0.5f + 0.5f;
    return glm::ivec2(uv * glm::vec2(float(width), float(height)));
}

class GpuFixture : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        RuntimeOptions o;
        o.validation = true;
        auto rt = Runtime::create(o);
        ASSERT_TRUE(rt.has_value()) << rt.error().describe();
        s_runtime = std::move(*rt).release();
    }
    static void TearDownTestSuite() {
        delete s_runtime;
        s_runtime = nullptr;
    }
    void SetUp() override {
        ASSERT_NE(s_runtime, nullptr);
        m_messagesBefore = s_runtime->gpu().validationMessageCount();
    }
    void TearDown() override {
        ASSERT_NE(s_runtime, nullptr);
        EXPECT_EQ(s_runtime->gpu().validationMessageCount(), m_messagesBefore)
            << (s_runtime->gpu().validationMessages().empty()
                    ? ""
                    : s_runtime->gpu().validationMessages().back());
    }
    static Runtime& rt() { return *s_runtime; }

    // Options to render Lua scene `scene` (with its scene.args) at width x height with manual
    // exposure (the scene camera's settings, no adaptation), as most GPU tests do.
    static SessionOptions sceneOptions(const std::string& scene,
                                       const std::map<std::string, std::string>& args,
                                       uint32_t width, uint32_t height) {
        SessionOptions o;
        o.scene = scene;
        o.sceneArgs = args;
        o.compile.outputWidth = width;
        o.compile.outputHeight = height;
        o.params["exposure_mode"] = Value("manual");
        o.paramsIfDeclared["taa_jitter"] = Value(false);   // pixels compared one by one
        o.paramsIfDeclared["specular_aa"] = Value(false);  // roughness as the scene gives it
        return o;
    }

    // What renderAndRead read back: textures by name, buffers' bytes by name, and the
    // pre-exposure the last frame was rendered with (1 when the pipeline has no exposure state).
    struct Readback {
        std::map<std::string, Image> images;
        std::map<std::string, std::vector<uint8_t>> buffers;
        float preExposure = 1.0f;
        const Image& operator[](const std::string& name) const { return images.at(name); }
    };
    // Loads `pipeline` with `options` (the resources to read are added to its captures), renders
    // `frames` frames and reads the textures and buffers back. Failures are test failures; what
    // could not be read is absent.
    static Readback renderAndRead(SessionOptions options, const std::string& pipeline,
                                  uint32_t frames, const std::vector<std::string>& textures,
                                  const std::vector<std::string>& buffers = {}) {
        for (const auto& name : textures) options.captures.push_back(name);
        for (const auto& name : buffers) options.captures.push_back(name);
        Session s(*s_runtime, options);
        Readback out;
        auto r = s.load(pipeline);
        EXPECT_TRUE(r.has_value()) << r.error().describe();
        if (!r) return out;
        for (uint32_t f = 0; f < frames; ++f) {
            auto fr = s.frame();
            EXPECT_TRUE(fr.has_value()) << fr.error().describe();
            if (!fr) return out;
        }
        for (const auto& name : textures) {
            auto img = s_runtime->executor().readback(name);
            EXPECT_TRUE(img.has_value()) << name;
            if (img) out.images[name] = std::move(*img);
        }
        for (const auto& name : buffers) {
            auto bytes = s_runtime->executor().readbackBuffer(name);
            EXPECT_TRUE(bytes.has_value()) << name;
            if (bytes) out.buffers[name] = std::move(*bytes);
        }
        if (auto state = s_runtime->executor().readbackBuffer("exposure");
            state && state->size() >= 16)
            std::memcpy(&out.preExposure, state->data() + 8, sizeof(float));
        return out;
    }

    // The default pipeline's HDR of `scene` at width x height, with the levels of detail or with
    // every mesh in full (RG_LOD=0).
    static Image renderHdr(const std::string& scene, bool levelsOfDetail, uint32_t width,
                           uint32_t height) {
        if (!levelsOfDetail) setenv("RG_LOD", "0", 1);
        Readback r = renderAndRead(sceneOptions(scene, {}, width, height),
                                   std::string(RG_SOURCE_ROOT) + "/scripts/pipelines/deferred.lua",
                                   1, {"hdr"});
        unsetenv("RG_LOD");
        return r.images.empty() ? Image() : r["hdr"];
    }

    inline static Runtime* s_runtime = nullptr;
    uint32_t m_messagesBefore = 0;
};

}  // namespace rg

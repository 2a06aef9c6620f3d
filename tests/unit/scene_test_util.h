// What the CPU scene tests (tests/unit/test_scene*.cpp) share: a fresh folder per test, file
// writing, a builder of glTF documents and their buffers, and comparisons.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "image/image.h"
#include "scene/scene.h"

namespace rg::test {

namespace fs = std::filesystem;
using nlohmann::json;

// A fresh folder per test under the build's temp folder.
inline std::string tmpDir(const std::string& name) {
    const fs::path dir = fs::path(RG_TEST_TMP) / ("scene_" + name);
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir.string();
}

inline void writeText(const std::string& path, const std::string& text) {
    std::ofstream out(path, std::ios::binary);
    out << text;
    ASSERT_TRUE(out.good()) << path;
}

inline void writeBytes(const std::string& path, const std::vector<unsigned char>& bytes) {
    std::ofstream out(path, std::ios::binary);
    out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
    ASSERT_TRUE(out.good()) << path;
}

inline std::vector<unsigned char> readBytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::vector<unsigned char>(std::istreambuf_iterator<char>(in),
                                      std::istreambuf_iterator<char>());
}

inline constexpr int kFloat = 5126, kUByte = 5121, kUShort = 5123, kUInt = 5125;

// Builds a glTF document and its binary buffer; writes .gltf + .bin or a .glb.
struct GltfBuilder {
    json j = {{"asset", {{"version", "2.0"}}}};
    std::vector<unsigned char> bin;
    json moreBuffers = json::array();  // buffers 1, 2, ... after the one `bin` becomes

    int view(const void* data, size_t size) {
        while (bin.size() % 4) bin.push_back(0);
        const size_t offset = bin.size();
        const auto* p = static_cast<const unsigned char*>(data);
        bin.insert(bin.end(), p, p + size);
        j["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", size}});
        return int(j["bufferViews"].size() - 1);
    }
    int accessor(int view, int componentType, size_t count, const std::string& type,
                 bool normalized = false) {
        json a = {{"bufferView", view},
                  {"componentType", componentType},
                  {"count", count},
                  {"type", type}};
        if (normalized) a["normalized"] = true;
        j["accessors"].push_back(a);
        return int(j["accessors"].size() - 1);
    }
    int floats(const std::vector<float>& v, const std::string& type) {
        const size_t n = type == "VEC2" ? 2 : type == "VEC3" ? 3 : type == "VEC4" ? 4 : 1;
        return accessor(view(v.data(), v.size() * 4), kFloat, v.size() / n, type);
    }
    int indices16(const std::vector<uint16_t>& v) {
        return accessor(view(v.data(), v.size() * 2), kUShort, v.size(), "SCALAR");
    }
    int indices8(const std::vector<uint8_t>& v) {
        return accessor(view(v.data(), v.size()), kUByte, v.size(), "SCALAR");
    }

    // A mesh with one primitive per entry of `prims` (attributes object + optional indices/material).
    int mesh(const std::string& name, const json& prims) {
        j["meshes"].push_back({{"name", name}, {"primitives", prims}});
        return int(j["meshes"].size() - 1);
    }
    int node(const json& n) {
        j["nodes"].push_back(n);
        return int(j["nodes"].size() - 1);
    }
    void scene(const std::vector<int>& roots) {
        j["scenes"] = json::array({{{"nodes", roots}}});
        j["scene"] = 0;
    }

    std::string writeGltf(const std::string& dir, const std::string& name,
                          const std::string& binName = "") {
        json doc = j;
        if (!bin.empty()) {
            const std::string b = binName.empty() ? name + ".bin" : binName;
            doc["buffers"] = json::array({{{"uri", b}, {"byteLength", bin.size()}}});
            writeBytes(dir + "/" + b, bin);
        }
        for (const json& b : moreBuffers) doc["buffers"].push_back(b);
        const std::string path = dir + "/" + name + ".gltf";
        writeText(path, doc.dump(1));
        return path;
    }
    std::string writeGlb(const std::string& dir, const std::string& name) {
        json doc = j;
        std::vector<unsigned char> b = bin;
        while (b.size() % 4) b.push_back(0);
        if (!b.empty()) doc["buffers"] = json::array({{{"byteLength", bin.size()}}});
        for (const json& extra : moreBuffers) doc["buffers"].push_back(extra);
        std::string text = doc.dump();
        while (text.size() % 4) text += ' ';
        std::vector<unsigned char> out;
        auto u32 = [&](uint32_t v) {
            unsigned char c[4];
            std::memcpy(c, &v, 4);
            out.insert(out.end(), c, c + 4);
        };
        out.insert(out.end(), {'g', 'l', 'T', 'F'});
        u32(2);
        u32(uint32_t(12 + 8 + text.size() + (b.empty() ? 0 : 8 + b.size())));
        u32(uint32_t(text.size()));
        u32(0x4E4F534Au);
        out.insert(out.end(), text.begin(), text.end());
        if (!b.empty()) {
            u32(uint32_t(b.size()));
            u32(0x004E4942u);
            out.insert(out.end(), b.begin(), b.end());
        }
        const std::string path = dir + "/" + name + ".glb";
        writeBytes(path, out);
        return path;
    }
};

// A unit quad in the XY plane facing +Z: u along +x, v downwards (v = 0 at y = 1).
inline void addQuad(GltfBuilder& g, bool withNormals, bool withUv = true) {
    std::vector<float> pos = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
    std::vector<float> nrm = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
    std::vector<float> uv = {0, 1, 1, 1, 1, 0, 0, 0};
    json attrs = {{"POSITION", g.floats(pos, "VEC3")}};
    if (withNormals) attrs["NORMAL"] = g.floats(nrm, "VEC3");
    if (withUv) attrs["TEXCOORD_0"] = g.floats(uv, "VEC2");
    const int idx = g.indices16({0, 1, 2, 0, 2, 3});
    g.mesh("quad", json::array({{{"attributes", attrs}, {"indices", idx}}}));
}

inline glm::vec3 origin(const glm::mat4& m) { return glm::vec3(m[3]); }

inline void expectNear(glm::vec3 a, glm::vec3 b, float tol, const std::string& what) {
    EXPECT_NEAR(a.x, b.x, tol) << what;
    EXPECT_NEAR(a.y, b.y, tol) << what;
    EXPECT_NEAR(a.z, b.z, tol) << what;
}

inline std::string errorOf(const rg::Result<rg::Scene>& r) {
    return r ? std::string("(loaded)") : r.error().message;
}

// A PNG with the given RGBA values (in [0, 1], stored as 8 bits).
inline std::string writeTestPng(const std::string& path, uint32_t w, uint32_t h,
                                const std::vector<float>& rgba) {
    rg::Image img(w, h, 4);
    img.pixels = rgba;
    auto r = rg::writePng(path, img);
    EXPECT_TRUE(r) << r.error().message;
    return path;
}

// A scene script of scripts/scenes.
inline std::string scenePath(const std::string& name) {
    return std::string(RG_SOURCE_ROOT) + "/scripts/scenes/" + name;
}

}  // namespace rg::test

// The CPU scene: glTF loading (hierarchy, primitives, generated normals and tangents, textures,
// sRGB, KHR_texture_transform, alpha, lights, emissive strength, required extensions), the
// exact error text of each kind of broken file, Lua scene scripts and their schema errors, the
// glTF writer's round trip, and CPU mip chains. No GPU. The glTF files are generated here.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "image/image.h"
#include "scene/scene.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

using rg::ErrorCode;

// A fresh folder per test under the build's temp folder.
std::string tmpDir(const std::string& name) {
    const fs::path dir = fs::path(RG_TEST_TMP) / ("scene_" + name);
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir.string();
}

void writeText(const std::string& path, const std::string& text) {
    std::ofstream out(path, std::ios::binary);
    out << text;
    ASSERT_TRUE(out.good()) << path;
}

void writeBytes(const std::string& path, const std::vector<unsigned char>& bytes) {
    std::ofstream out(path, std::ios::binary);
    out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
    ASSERT_TRUE(out.good()) << path;
}

std::vector<unsigned char> readBytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::vector<unsigned char>(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

constexpr int kFloat = 5126, kUByte = 5121, kUShort = 5123, kUInt = 5125;

// Builds a glTF document and its binary buffer; writes .gltf + .bin or a .glb.
struct GltfBuilder {
    json j = {{"asset", {{"version", "2.0"}}}};
    std::vector<unsigned char> bin;

    int view(const void* data, size_t size) {
        while (bin.size() % 4) bin.push_back(0);
        const size_t offset = bin.size();
        const auto* p = static_cast<const unsigned char*>(data);
        bin.insert(bin.end(), p, p + size);
        j["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", size}});
        return int(j["bufferViews"].size() - 1);
    }
    int accessor(int view, int componentType, size_t count, const std::string& type, bool normalized = false) {
        json a = {{"bufferView", view}, {"componentType", componentType}, {"count", count}, {"type", type}};
        if (normalized) a["normalized"] = true;
        j["accessors"].push_back(a);
        return int(j["accessors"].size() - 1);
    }
    int floats(const std::vector<float>& v, const std::string& type) {
        const size_t n = type == "VEC2" ? 2 : type == "VEC3" ? 3 : type == "VEC4" ? 4 : 1;
        return accessor(view(v.data(), v.size() * 4), kFloat, v.size() / n, type);
    }
    int indices16(const std::vector<uint16_t>& v) { return accessor(view(v.data(), v.size() * 2), kUShort, v.size(), "SCALAR"); }
    int indices8(const std::vector<uint8_t>& v) { return accessor(view(v.data(), v.size()), kUByte, v.size(), "SCALAR"); }

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

    std::string writeGltf(const std::string& dir, const std::string& name, const std::string& binName = "") {
        json doc = j;
        if (!bin.empty()) {
            const std::string b = binName.empty() ? name + ".bin" : binName;
            doc["buffers"] = json::array({{{"uri", b}, {"byteLength", bin.size()}}});
            writeBytes(dir + "/" + b, bin);
        }
        const std::string path = dir + "/" + name + ".gltf";
        writeText(path, doc.dump(1));
        return path;
    }
    std::string writeGlb(const std::string& dir, const std::string& name) {
        json doc = j;
        std::vector<unsigned char> b = bin;
        while (b.size() % 4) b.push_back(0);
        if (!b.empty()) doc["buffers"] = json::array({{{"byteLength", bin.size()}}});
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
void addQuad(GltfBuilder& g, bool withNormals, bool withUv = true) {
    std::vector<float> pos = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
    std::vector<float> nrm = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
    std::vector<float> uv = {0, 1, 1, 1, 1, 0, 0, 0};
    json attrs = {{"POSITION", g.floats(pos, "VEC3")}};
    if (withNormals) attrs["NORMAL"] = g.floats(nrm, "VEC3");
    if (withUv) attrs["TEXCOORD_0"] = g.floats(uv, "VEC2");
    const int idx = g.indices16({0, 1, 2, 0, 2, 3});
    g.mesh("quad", json::array({{{"attributes", attrs}, {"indices", idx}}}));
}

glm::vec3 origin(const glm::mat4& m) { return glm::vec3(m[3]); }

void expectNear(glm::vec3 a, glm::vec3 b, float tol, const std::string& what) {
    EXPECT_NEAR(a.x, b.x, tol) << what;
    EXPECT_NEAR(a.y, b.y, tol) << what;
    EXPECT_NEAR(a.z, b.z, tol) << what;
}

std::string errorOf(const rg::Result<rg::Scene>& r) { return r ? std::string("(loaded)") : r.error().message; }

// A PNG with the given RGBA values (in [0, 1], stored as 8 bits).
std::string writeTestPng(const std::string& path, uint32_t w, uint32_t h, const std::vector<float>& rgba) {
    rg::Image img(w, h, 4);
    img.pixels = rgba;
    auto r = rg::writePng(path, img);
    EXPECT_TRUE(r) << r.error().message;
    return path;
}

// ---------------------------------------------------------------------------------------------
// glTF: structure

TEST(GltfLoad, ChildUnderTranslatedRotatedParentLandsAtTheRightWorldPosition) {
    const std::string dir = tmpDir("hierarchy");
    GltfBuilder g;
    addQuad(g, true);
    // Parent: translate (1, 2, 3), rotate +90° about Y (quaternion x, y, z, w). Child: (1, 0, 0).
    const float s = std::sqrt(0.5f);
    const int child = g.node({{"name", "child"}, {"mesh", 0}, {"translation", {1, 0, 0}}});
    const int parent = g.node({{"name", "parent"}, {"translation", {1, 2, 3}}, {"rotation", {0, s, 0, s}}, {"children", {child}}});
    // The same through a matrix: translate (0, 0, -5), scale 2; its child at (0, 1, 0).
    const int child2 = g.node({{"name", "child2"}, {"mesh", 0}, {"translation", {0, 1, 0}}});
    const int parent2 = g.node({{"name", "parent2"}, {"matrix", {2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 2, 0, 0, 0, -5, 1}}, {"children", {child2}}});
    g.scene({parent, parent2});
    auto scene = rg::loadGltf(g.writeGltf(dir, "h"));
    ASSERT_TRUE(scene) << errorOf(scene);
    ASSERT_EQ(scene->nodes.size(), 2u);
    EXPECT_EQ(scene->nodes[0].name, "child");
    // R_y(90°) maps +x to -z: (1, 2, 3) + (0, 0, -1).
    expectNear(origin(scene->nodes[0].world), {1, 2, 2}, 1e-5f, "child origin");
    // The quad's corner (1, 0, 0) goes to child (1,0,0)+(1,0,0) -> rotated (0,0,-2) -> (1, 2, 1).
    expectNear(glm::vec3(scene->nodes[0].world * glm::vec4(1, 0, 0, 1)), {1, 2, 1}, 1e-5f, "corner");
    expectNear(origin(scene->nodes[1].world), {0, 2, -5}, 1e-5f, "matrix child origin");
    // Bounds cover both placed quads.
    expectNear(scene->boundsMin, {0, 2, -5}, 1e-5f, "boundsMin");
    expectNear(scene->boundsMax, {2, 4, 2}, 1e-5f, "boundsMax");
}

TEST(GltfLoad, SeveralPrimitivesIndexedAndNot) {
    const std::string dir = tmpDir("prims");
    GltfBuilder g;
    const int pos = g.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
    const int nrm = g.floats({0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3");
    const int idx8 = g.indices8({0, 1, 2});
    g.j["materials"] = json::array({{{"name", "a"}}, {{"name", "b"}}});
    g.mesh("two", json::array({{{"attributes", {{"POSITION", pos}, {"NORMAL", nrm}}}, {"indices", idx8}, {"material", 1}},
                               {{"attributes", {{"POSITION", pos}, {"NORMAL", nrm}}}, {"material", 0}},
                               {{"attributes", {{"POSITION", pos}, {"NORMAL", nrm}}}}}));
    g.scene({g.node({{"mesh", 0}})});
    auto scene = rg::loadGltf(g.writeGltf(dir, "p"));
    ASSERT_TRUE(scene) << errorOf(scene);
    ASSERT_EQ(scene->meshes.size(), 1u);
    const auto& prims = scene->meshes[0].primitives;
    ASSERT_EQ(prims.size(), 3u);
    EXPECT_EQ(prims[0].material, 1u);
    EXPECT_EQ(prims[1].material, 0u);
    EXPECT_EQ(prims[0].indices, (std::vector<uint32_t>{0, 1, 2}));
    EXPECT_EQ(prims[1].indices, (std::vector<uint32_t>{0, 1, 2}));  // generated for a non-indexed primitive
    // No material: glTF's default (white, metallic 1, roughness 1), appended after the file's.
    ASSERT_EQ(scene->materials.size(), 3u);
    EXPECT_EQ(prims[2].material, 2u);
    EXPECT_EQ(scene->materials[2].name, "default");
    EXPECT_FLOAT_EQ(scene->materials[2].metalMask, 1.0f);
    EXPECT_FLOAT_EQ(scene->materials[2].smoothness, 0.0f);
    EXPECT_EQ(scene->nodes[0].name, "two");  // an unnamed node takes its mesh's name
}

TEST(GltfLoad, TriangleStripAndFanBecomeCounterClockwiseLists) {
    const std::string dir = tmpDir("strip");
    GltfBuilder g;
    const int pos = g.floats({0, 0, 0, 0, 1, 0, 1, 0, 0, 1, 1, 0}, "VEC3");  // zig-zag strip facing +Z
    const int nrm = g.floats({0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3");
    g.mesh("m", json::array({{{"attributes", {{"POSITION", pos}, {"NORMAL", nrm}}}, {"mode", 5}},
                             {{"attributes", {{"POSITION", pos}, {"NORMAL", nrm}}}, {"mode", 6}}}));
    g.scene({g.node({{"mesh", 0}})});
    auto scene = rg::loadGltf(g.writeGltf(dir, "s"));
    ASSERT_TRUE(scene) << errorOf(scene);
    const auto& strip = scene->meshes[0].primitives[0];
    EXPECT_EQ(strip.indices, (std::vector<uint32_t>{0, 1, 2, 2, 1, 3}));
    EXPECT_EQ(scene->meshes[0].primitives[1].indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3}));
    for (size_t t = 0; t < strip.indices.size(); t += 3) {
        const glm::vec3 a = strip.vertices[strip.indices[t]].position, b = strip.vertices[strip.indices[t + 1]].position,
                        c = strip.vertices[strip.indices[t + 2]].position;
        // The strip's first triangle (0,1,2) is clockwise seen from +Z, so both face -Z alike.
        EXPECT_LT(glm::cross(b - a, c - a).z, 0.0f) << "triangle " << t / 3;
    }
}

TEST(GltfLoad, GeneratedTangentsAreOrthogonalToNormalsAndFollowPlusU) {
    const std::string dir = tmpDir("tangents");
    GltfBuilder g;
    addQuad(g, true);
    // The same quad with u mirrored (u grows along -x): the tangent flips, handedness too.
    const int pos = g.floats({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0}, "VEC3");
    const int nrm = g.floats({0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3");
    const int uv = g.floats({1, 1, 0, 1, 0, 0, 1, 0}, "VEC2");
    g.mesh("mirrored", json::array({{{"attributes", {{"POSITION", pos}, {"NORMAL", nrm}, {"TEXCOORD_0", uv}}}, {"indices", g.indices16({0, 1, 2, 0, 2, 3})}}}));
    g.scene({g.node({{"mesh", 0}}), g.node({{"mesh", 1}})});
    auto scene = rg::loadGltf(g.writeGltf(dir, "t"));
    ASSERT_TRUE(scene) << errorOf(scene);
    for (const auto& v : scene->meshes[0].primitives[0].vertices) {
        EXPECT_NEAR(glm::dot(glm::vec3(v.tangent), v.normal), 0.0f, 1e-6f);
        expectNear(glm::vec3(v.tangent), {1, 0, 0}, 1e-6f, "tangent along +u = +x");
        EXPECT_EQ(v.tangent.w, 1.0f);  // bitangent cross(n, t) = +y = -dP/dv (v grows downwards)
    }
    for (const auto& v : scene->meshes[1].primitives[0].vertices) {
        expectNear(glm::vec3(v.tangent), {-1, 0, 0}, 1e-6f, "mirrored tangent");
        EXPECT_EQ(v.tangent.w, -1.0f);
    }
}

TEST(GltfLoad, TangentsOfAnIrregularMeshAreUnitAndOrthogonal) {
    // generateTangents on a bumpy grid with skewed uvs.
    rg::Primitive p;
    const int n = 8;
    for (int y = 0; y <= n; ++y)
        for (int x = 0; x <= n; ++x) {
            rg::Vertex v;
            v.position = glm::vec3(x, y, 0.3f * std::sin(float(x + 2 * y)));
            v.normal = glm::normalize(glm::vec3(0.2f * std::cos(float(x)), 0.1f, 1.0f));
            v.uv0 = glm::vec2(float(x) / n + 0.1f * float(y) / n, 1.0f - float(y) / n);
            p.vertices.push_back(v);
        }
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            const uint32_t a = uint32_t(y * (n + 1) + x), b = a + 1, c = a + uint32_t(n + 1), d = c + 1;
            p.indices.insert(p.indices.end(), {a, b, d, a, d, c});
        }
    rg::generateTangents(p);
    for (const auto& v : p.vertices) {
        EXPECT_NEAR(glm::length(glm::vec3(v.tangent)), 1.0f, 1e-5f);
        EXPECT_NEAR(glm::dot(glm::vec3(v.tangent), v.normal), 0.0f, 1e-5f);
        EXPECT_GT(v.tangent.x, 0.5f);  // u grows with x
        EXPECT_EQ(v.tangent.w, 1.0f);
    }
}

TEST(GltfLoad, MissingNormalsBecomeFlatNormals) {
    const std::string dir = tmpDir("flat");
    GltfBuilder g;
    // Two triangles sharing an edge at a right angle: one faces +Z, the other +X.
    const int pos = g.floats({0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 0, 0, 1, 0, 0, 0, -1}, "VEC3");
    g.mesh("fold", json::array({{{"attributes", {{"POSITION", pos}}}, {"indices", g.indices16({0, 1, 2, 0, 5, 4})}}}));
    g.scene({g.node({{"mesh", 0}})});
    auto scene = rg::loadGltf(g.writeGltf(dir, "f"));
    ASSERT_TRUE(scene) << errorOf(scene);
    const auto& p = scene->meshes[0].primitives[0];
    ASSERT_EQ(p.vertices.size(), 6u);  // unwelded: each triangle its own vertices
    for (int k = 0; k < 3; ++k) expectNear(p.vertices[size_t(k)].normal, {0, 0, 1}, 1e-6f, "first face");
    for (int k = 3; k < 6; ++k) expectNear(p.vertices[size_t(k)].normal, {1, 0, 0}, 1e-6f, "second face");
    for (const auto& v : p.vertices) EXPECT_NEAR(glm::dot(glm::vec3(v.tangent), v.normal), 0.0f, 1e-6f);
}

TEST(GltfLoad, NormalizedIntegerTexcoordsAndSecondUvSet) {
    const std::string dir = tmpDir("uvtypes");
    GltfBuilder g;
    const int pos = g.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
    const uint8_t uvb[6] = {0, 255, 255, 255, 0, 0};
    const uint16_t uvs[6] = {0, 65535, 32768, 65535, 0, 0};
    const int uv0 = g.accessor(g.view(uvb, 6), kUByte, 3, "VEC2", true);
    const int uv1 = g.accessor(g.view(uvs, 12), kUShort, 3, "VEC2", true);
    g.mesh("m", json::array({{{"attributes", {{"POSITION", pos}, {"TEXCOORD_0", uv0}, {"TEXCOORD_1", uv1}}}}}));
    g.scene({g.node({{"mesh", 0}})});
    auto scene = rg::loadGltf(g.writeGltf(dir, "u"));
    ASSERT_TRUE(scene) << errorOf(scene);
    const auto& v = scene->meshes[0].primitives[0].vertices;
    EXPECT_EQ(v[1].uv0, glm::vec2(1.0f, 1.0f));
    EXPECT_EQ(v[0].uv0, glm::vec2(0.0f, 1.0f));
    EXPECT_NEAR(v[1].uv1.x, 32768.0f / 65535.0f, 1e-7f);
    EXPECT_EQ(v[1].uv1.y, 1.0f);
}

// ---------------------------------------------------------------------------------------------
// glTF: materials, textures, lights, cameras

TEST(GltfLoad, MaterialMappingSrgbFlagsAndTextureTransform) {
    const std::string dir = tmpDir("materials");
    // 2x1: a mid sRGB grey and white.
    writeTestPng(dir + "/albedo.png", 2, 1, {128 / 255.0f, 128 / 255.0f, 128 / 255.0f, 1, 1, 1, 1, 1});
    writeTestPng(dir + "/data.png", 1, 1, {0.25f, 0.5f, 0.75f, 1});
    GltfBuilder g;
    addQuad(g, true);
    g.j["images"] = json::array({{{"uri", "albedo.png"}}, {{"uri", "data.png"}}});
    g.j["samplers"] = json::array({{{"magFilter", 9728}, {"minFilter", 9985}, {"wrapS", 33071}, {"wrapT", 33648}}});
    g.j["textures"] = json::array({{{"source", 0}, {"sampler", 0}}, {{"source", 1}}});
    const float half = 3.14159265f / 2;
    g.j["materials"] = json::array({{
        {"name", "m"},
        {"pbrMetallicRoughness",
         {{"baseColorFactor", {0.5, 0.25, 1.0, 0.75}},
          {"metallicFactor", 0.2},
          {"roughnessFactor", 0.3},
          {"baseColorTexture",
           {{"index", 0},
            {"extensions", {{"KHR_texture_transform", {{"offset", {0.5, 0.25}}, {"rotation", half}, {"scale", {2, 3}}, {"texCoord", 1}}}}}}},
          {"metallicRoughnessTexture", {{"index", 1}}}}},
        {"normalTexture", {{"index", 1}, {"scale", 0.5}}},
        {"occlusionTexture", {{"index", 1}, {"strength", 0.7}, {"texCoord", 1}}},
        {"emissiveTexture", {{"index", 0}}},
        {"emissiveFactor", {1.0, 0.5, 0.25}},
        {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", 100.0}}}}},
    }});
    g.j["extensionsUsed"] = {"KHR_texture_transform", "KHR_materials_emissive_strength"};
    g.j["meshes"][0]["primitives"][0]["material"] = 0;
    g.scene({g.node({{"mesh", 0}})});
    auto scene = rg::loadGltf(g.writeGltf(dir, "m"));
    ASSERT_TRUE(scene) << errorOf(scene);
    const rg::Material& m = scene->materials.at(0);
    EXPECT_EQ(m.baseColor, glm::vec3(0.5f, 0.25f, 1.0f));
    EXPECT_FLOAT_EQ(m.opacity, 0.75f);
    EXPECT_FLOAT_EQ(m.metalMask, 0.2f);
    EXPECT_FLOAT_EQ(m.smoothness, 0.7f);   // 1 - perceptual roughness
    EXPECT_FLOAT_EQ(m.reflectance, 0.5f);  // f0 = 0.04
    expectNear(m.emissive, {100, 50, 25}, 1e-4f, "emissive = factor x strength, in nits");
    EXPECT_FLOAT_EQ(m.normalScale, 0.5f);
    EXPECT_FLOAT_EQ(m.occlusionStrength, 0.7f);
    EXPECT_EQ(m.occlusionTex.texCoord, 1u);

    // albedo.png is used by base colour and emissive (sRGB); data.png by three linear maps.
    ASSERT_EQ(scene->images.size(), 2u);
    EXPECT_EQ(m.baseColorTex.image, m.emissiveTex.image);
    EXPECT_EQ(m.metallicRoughnessTex.image, m.normalTex.image);
    EXPECT_EQ(m.normalTex.image, m.occlusionTex.image);
    const rg::SceneImage& albedo = scene->images[size_t(m.baseColorTex.image)];
    const rg::SceneImage& data = scene->images[size_t(m.normalTex.image)];
    EXPECT_TRUE(albedo.srgb);
    EXPECT_FALSE(data.srgb);
    EXPECT_EQ(albedo.name, "albedo.png");
    // Pixels hold the file's encoded values; decoding 128/255 gives 0.2158605 linear.
    EXPECT_FLOAT_EQ(albedo.pixels.at(0, 0, 0), 128 / 255.0f);
    EXPECT_NEAR(rg::srgbDecode(albedo.pixels.at(0, 0, 0)), 0.2158605f, 1e-6f);
    EXPECT_FLOAT_EQ(data.pixels.at(0, 0, 2), 191 / 255.0f);
    EXPECT_EQ(albedo.pixels.channels, 4u);

    // Sampler: NEAREST mag, LINEAR_MIPMAP_NEAREST min, clamp / mirrored; texture 1 has none.
    ASSERT_EQ(scene->samplers.size(), 1u);
    EXPECT_EQ(m.baseColorTex.sampler, 0);
    EXPECT_EQ(m.normalTex.sampler, -1);
    const rg::SamplerDesc& s = scene->samplers[0];
    EXPECT_EQ(s.magFilter, rg::Filter::Nearest);
    EXPECT_EQ(s.minFilter, rg::Filter::Linear);
    EXPECT_EQ(s.mipmapMode, rg::MipmapMode::Nearest);
    EXPECT_EQ(s.wrapS, rg::Wrap::ClampToEdge);
    EXPECT_EQ(s.wrapT, rg::Wrap::MirroredRepeat);

    // KHR_texture_transform: uv' = T(offset) R(rotation) S(scale) uv; texCoord overridden to 1.
    EXPECT_EQ(m.baseColorTex.texCoord, 1u);
    const glm::vec3 u = m.baseColorTex.transform * glm::vec3(1, 0, 1);  // S: (2,0); R(90°): (0,-2); T: (0.5,-1.75)
    EXPECT_NEAR(u.x, 0.5f, 1e-6f);
    EXPECT_NEAR(u.y, -1.75f, 1e-6f);
    const glm::vec3 v = m.baseColorTex.transform * glm::vec3(0, 1, 1);  // S: (0,3); R: (3,0); T: (3.5,0.25)
    EXPECT_NEAR(v.x, 3.5f, 1e-6f);
    EXPECT_NEAR(v.y, 0.25f, 1e-6f);
    EXPECT_EQ(m.normalTex.transform, glm::mat3(1.0f));

    // Mips were generated: 2x1 -> 1x1, the sRGB pair averaged as light, not as code values.
    EXPECT_EQ(albedo.mipLevels, 2u);
    ASSERT_EQ(albedo.mips.size(), 1u);
    EXPECT_NEAR(albedo.mips[0].at(0, 0, 0), rg::srgbEncode((0.2158605f + 1.0f) / 2), 1e-5f);
    EXPECT_EQ(albedo.mips[0].at(0, 0, 3), 1.0f);
    // Every file read is listed for hot reload.
    EXPECT_EQ(scene->files.size(), 4u);  // .gltf, .bin, two images
}

TEST(GltfLoad, AlphaModesAndDoubleSided) {
    const std::string dir = tmpDir("alpha");
    GltfBuilder g;
    addQuad(g, true);
    g.j["materials"] = json::array({{{"name", "o"}},
                                    {{"name", "m"}, {"alphaMode", "MASK"}, {"alphaCutoff", 0.3}},
                                    {{"name", "b"}, {"alphaMode", "BLEND"}, {"doubleSided", true}}});
    g.scene({g.node({{"mesh", 0}})});
    auto scene = rg::loadGltf(g.writeGltf(dir, "a"));
    ASSERT_TRUE(scene) << errorOf(scene);
    EXPECT_EQ(scene->materials[0].alphaMode, rg::AlphaMode::Opaque);
    EXPECT_FALSE(scene->materials[0].doubleSided);
    EXPECT_EQ(scene->materials[1].alphaMode, rg::AlphaMode::Mask);
    EXPECT_FLOAT_EQ(scene->materials[1].alphaCutoff, 0.3f);
    EXPECT_EQ(scene->materials[2].alphaMode, rg::AlphaMode::Blend);
    EXPECT_TRUE(scene->materials[2].doubleSided);

    g.j["materials"][1]["alphaMode"] = "CUTOUT";
    auto bad = rg::loadGltf(g.writeGltf(dir, "a2"));
    EXPECT_EQ(errorOf(bad), "'" + dir + "/a2.gltf': material 1 'm': alphaMode 'CUTOUT', expected OPAQUE, MASK or BLEND");
}

TEST(GltfLoad, PunctualLightsKeepGltfUnitsAndTakeTheirNodeTransform) {
    const std::string dir = tmpDir("lights");
    GltfBuilder g;
    g.j["extensionsUsed"] = {"KHR_lights_punctual"};
    g.j["extensions"]["KHR_lights_punctual"]["lights"] = json::array(
        {{{"name", "bulb"}, {"type", "point"}, {"intensity", 5.0}, {"color", {1, 0.5, 0.25}}, {"range", 10}},
         {{"name", "spot"}, {"type", "spot"}, {"intensity", 20.0}, {"spot", {{"innerConeAngle", 0.2}, {"outerConeAngle", 0.6}}}},
         {{"name", "sun"}, {"type", "directional"}, {"intensity", 3.0}}});
    const float s = std::sqrt(0.5f);
    g.scene({g.node({{"translation", {1, 2, 3}}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}}),
             g.node({{"extensions", {{"KHR_lights_punctual", {{"light", 1}}}}}}),
             // -90° about X turns -Z into -Y: the sun shines straight down.
             g.node({{"rotation", {-s, 0, 0, s}}, {"extensions", {{"KHR_lights_punctual", {{"light", 2}}}}}})});
    auto scene = rg::loadGltf(g.writeGltf(dir, "l"));
    ASSERT_TRUE(scene) << errorOf(scene);
    ASSERT_EQ(scene->lights.size(), 3u);
    const rg::Light& bulb = scene->lights[0];
    EXPECT_EQ(bulb.type, rg::LightType::Point);
    EXPECT_EQ(bulb.unit, "cd");
    EXPECT_FLOAT_EQ(bulb.intensity, 5.0f);
    EXPECT_EQ(bulb.color, glm::vec3(1, 0.5f, 0.25f));
    EXPECT_FLOAT_EQ(bulb.range, 10.0f);
    expectNear(bulb.position, {1, 2, 3}, 1e-6f, "bulb position");
    const rg::Light& spot = scene->lights[1];
    EXPECT_EQ(spot.type, rg::LightType::Spot);
    EXPECT_EQ(spot.unit, "cd");
    EXPECT_FLOAT_EQ(spot.innerAngle, 0.2f);
    EXPECT_FLOAT_EQ(spot.outerAngle, 0.6f);
    expectNear(spot.direction, {0, 0, -1}, 1e-6f, "spot looks along -Z");
    const rg::Light& sun = scene->lights[2];
    EXPECT_EQ(sun.type, rg::LightType::Directional);
    EXPECT_EQ(sun.unit, "lux");
    expectNear(sun.direction, {0, -1, 0}, 1e-6f, "sun direction");
}

TEST(GltfLoad, PerspectiveCameraFromItsNode) {
    const std::string dir = tmpDir("camera");
    GltfBuilder g;
    g.j["cameras"] = json::array({{{"name", "cam"}, {"type", "perspective"}, {"perspective", {{"yfov", 0.6}, {"znear", 0.1}, {"zfar", 50}}}}});
    g.scene({g.node({{"camera", 0}, {"translation", {0, 1, 10}}})});
    auto scene = rg::loadGltf(g.writeGltf(dir, "c"));
    ASSERT_TRUE(scene) << errorOf(scene);
    ASSERT_EQ(scene->cameras.size(), 1u);
    const rg::Camera& c = scene->cameras[0];
    EXPECT_EQ(c.name, "cam");
    EXPECT_FLOAT_EQ(c.verticalFov, 0.6f);
    EXPECT_FLOAT_EQ(c.nearPlane, 0.1f);
    EXPECT_FLOAT_EQ(c.farPlane, 50.0f);
    expectNear(c.position, {0, 1, 10}, 1e-6f, "position");
    expectNear(c.target, {0, 1, 9}, 1e-6f, "target one metre along -Z");
    EXPECT_FLOAT_EQ(c.aperture, 16.0f);  // physical settings default to sunny 16
    EXPECT_FLOAT_EQ(c.shutter, 0.008f);
}

TEST(GltfLoad, OrthographicAndUnnamedCamerasAreKeptAndNamed) {
    // A perspective and an orthographic camera, both unnamed: both kept (the orthographic one was
    // dropped), named so that --camera can pick each, and the orthographic one's ymag is half its
    // height. An unknown type is an error naming the camera.
    const std::string dir = tmpDir("ortho_camera");
    GltfBuilder g;
    g.j["cameras"] = json::array({{{"type", "perspective"}, {"perspective", {{"yfov", 0.6}, {"znear", 0.1}}}},
                                  {{"type", "orthographic"}, {"orthographic", {{"xmag", 4}, {"ymag", 3}, {"znear", 0}, {"zfar", 100}}}}});
    g.scene({g.node({{"camera", 0}}), g.node({{"camera", 1}, {"translation", {0, 10, 0}}})});
    auto scene = rg::loadGltf(g.writeGltf(dir, "c"));
    ASSERT_TRUE(scene) << errorOf(scene);
    ASSERT_EQ(scene->cameras.size(), 2u);
    EXPECT_EQ(scene->cameras[0].name, "camera 0");
    EXPECT_FALSE(scene->cameras[0].orthographic);
    EXPECT_EQ(scene->cameras[1].name, "camera 1");
    EXPECT_TRUE(scene->cameras[1].orthographic);
    EXPECT_FLOAT_EQ(scene->cameras[1].orthoHeight, 6.0f);
    EXPECT_FLOAT_EQ(scene->cameras[1].farPlane, 100.0f);
    EXPECT_GT(scene->cameras[1].nearPlane, 0.0f);  // znear 0 is kept just above it
    // Written back out and read again: still orthographic, the same height.
    ASSERT_TRUE(rg::exportGlb(*scene, dir + "/c.glb").has_value());
    auto again = rg::loadGltf(dir + "/c.glb");
    ASSERT_TRUE(again) << errorOf(again);
    ASSERT_EQ(again->cameras.size(), 2u);
    EXPECT_TRUE(again->cameras[1].orthographic);
    EXPECT_FLOAT_EQ(again->cameras[1].orthoHeight, 6.0f);
    GltfBuilder bad;
    bad.j["cameras"] = json::array({{{"name", "fish"}, {"type", "fisheye"}}});
    bad.scene({bad.node({{"camera", 0}})});
    auto refused = rg::loadGltf(bad.writeGltf(dir, "bad"));
    ASSERT_FALSE(refused);
    EXPECT_NE(refused.error().message.find("fisheye"), std::string::npos) << refused.error().message;
}

TEST(GltfLoad, GlbWithAnEmbeddedImage) {
    const std::string dir = tmpDir("glb");
    writeTestPng(dir + "/t.png", 1, 1, {1, 0, 0, 1});
    auto png = readBytes(dir + "/t.png");
    GltfBuilder g;
    addQuad(g, true);
    const int view = g.view(png.data(), png.size());
    g.j["images"] = json::array({{{"bufferView", view}, {"mimeType", "image/png"}, {"name", "red"}}});
    g.j["textures"] = json::array({{{"source", 0}}});
    g.j["materials"] = json::array({{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}});
    g.j["meshes"][0]["primitives"][0]["material"] = 0;
    g.scene({g.node({{"mesh", 0}})});
    auto scene = rg::loadGltf(g.writeGlb(dir, "e"));
    ASSERT_TRUE(scene) << errorOf(scene);
    ASSERT_EQ(scene->images.size(), 1u);
    EXPECT_EQ(scene->images[0].name, "red");
    EXPECT_EQ(scene->images[0].pixels.at(0, 0, 0), 1.0f);
    EXPECT_EQ(scene->images[0].pixels.at(0, 0, 1), 0.0f);
    EXPECT_EQ(scene->meshes[0].primitives[0].vertices.size(), 4u);
}

// ---------------------------------------------------------------------------------------------
// glTF: every kind of broken file, with its exact message

TEST(GltfErrors, RequiredUnsupportedExtensionIsRefusedByName) {
    const std::string dir = tmpDir("ext");
    GltfBuilder g;
    addQuad(g, true);
    g.j["extensionsUsed"] = {"KHR_draco_mesh_compression", "KHR_texture_transform"};
    g.j["extensionsRequired"] = {"KHR_texture_transform", "KHR_draco_mesh_compression"};
    const std::string path = g.writeGlb(dir, "x");
    auto r = rg::loadGltf(path);
    ASSERT_FALSE(r);
    EXPECT_EQ(r.error().code, ErrorCode::Unsupported);
    EXPECT_EQ(r.error().message, "'" + path + "' requires extension 'KHR_draco_mesh_compression', which rgraph does not support");
    // Used but not required: loads, with a warning.
    g.j.erase("extensionsRequired");
    std::vector<std::string> warnings;
    rg::GltfOptions o;
    o.warnings = &warnings;
    ASSERT_TRUE(rg::loadGltf(g.writeGlb(dir, "y"), o));
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_EQ(warnings[0], "'" + dir + "/y.glb': uses extension 'KHR_draco_mesh_compression', which rgraph ignores");
}

TEST(GltfErrors, MissingFile) {
    const std::string path = tmpDir("missing") + "/nope.gltf";
    auto r = rg::loadGltf(path);
    ASSERT_FALSE(r);
    EXPECT_EQ(r.error().code, ErrorCode::NotFound);
    EXPECT_EQ(r.error().message, "cannot open '" + path + "': No such file or directory");
}

TEST(GltfErrors, BrokenJson) {
    const std::string dir = tmpDir("json");
    writeText(dir + "/b.gltf", "{\n  \"asset\": {\"version\": \"2.0\"},\n  \"nodes\": [ }\n");
    auto r = rg::loadGltf(dir + "/b.gltf");
    EXPECT_EQ(errorOf(r), "'" + dir +
                              "/b.gltf': invalid JSON at line 3, column 14: syntax error while parsing value - unexpected '}'; "
                              "expected '[', '{', or a literal");
    // Garbage bytes and valid JSON that is not a glTF.
    writeBytes(dir + "/g.gltf", {0x00, 0xff, 0x13, 0x37});
    EXPECT_EQ(errorOf(rg::loadGltf(dir + "/g.gltf")).rfind("'" + dir + "/g.gltf': invalid JSON at line 1, column 1:", 0), 0u)
        << errorOf(rg::loadGltf(dir + "/g.gltf"));
    writeText(dir + "/a.gltf", "[1, 2]");
    EXPECT_EQ(errorOf(rg::loadGltf(dir + "/a.gltf")), "'" + dir + "/a.gltf': invalid glTF: the top level is not a JSON object");
    writeText(dir + "/v.gltf", "{}");
    EXPECT_EQ(errorOf(rg::loadGltf(dir + "/v.gltf")), "'" + dir + "/v.gltf': invalid glTF: no asset.version (is this a glTF file?)");
    writeText(dir + "/old.gltf", R"({"asset": {"version": "1.0"}})");
    auto old = rg::loadGltf(dir + "/old.gltf");
    ASSERT_FALSE(old);
    EXPECT_EQ(old.error().code, ErrorCode::Unsupported);
    EXPECT_EQ(old.error().message, "'" + dir + "/old.gltf': glTF version 1.0 is not supported (only 2.x)");
    // What tinygltf itself refuses comes through with its reason.
    writeText(dir + "/t.gltf", R"({"asset": {"version": "2.0"}, "accessors": [{"count": 1, "type": "VEC3"}]})");
    EXPECT_EQ(errorOf(rg::loadGltf(dir + "/t.gltf")).rfind("'" + dir + "/t.gltf': invalid glTF: ", 0), 0u);
}

TEST(GltfErrors, TruncatedGlb) {
    const std::string dir = tmpDir("trunc");
    GltfBuilder g;
    addQuad(g, true);
    g.scene({g.node({{"mesh", 0}})});
    auto bytes = readBytes(g.writeGlb(dir, "t"));
    bytes.resize(bytes.size() - 40);
    writeBytes(dir + "/t.glb", bytes);
    EXPECT_EQ(errorOf(rg::loadGltf(dir + "/t.glb")), "'" + dir + "/t.glb': truncated GLB: the header says " +
                                                         std::to_string(bytes.size() + 40) + " bytes, the file has " +
                                                         std::to_string(bytes.size()));
}

TEST(GltfErrors, MissingBuffer) {
    const std::string dir = tmpDir("buffer");
    GltfBuilder g;
    addQuad(g, true);
    g.scene({g.node({{"mesh", 0}})});
    const std::string path = g.writeGltf(dir, "scene", "scene.bin");
    fs::remove(dir + "/scene.bin");
    auto r = rg::loadGltf(path);
    EXPECT_EQ(errorOf(r), "'" + path + "': buffer 0 'scene.bin': cannot open '" + dir + "/scene.bin': No such file or directory");
    // Too short for its byteLength.
    writeBytes(dir + "/scene.bin", std::vector<unsigned char>(10));
    EXPECT_EQ(errorOf(rg::loadGltf(path)), "'" + path + "': buffer 0 'scene.bin': the file has 10 bytes, byteLength says " +
                                               std::to_string(g.bin.size()));
}

TEST(GltfErrors, MissingOrUndecodableImage) {
    const std::string dir = tmpDir("image");
    GltfBuilder g;
    addQuad(g, true);
    g.j["images"] = json::array({{{"uri", "missing.png"}}});
    g.j["textures"] = json::array({{{"source", 0}}});
    g.j["materials"] = json::array({{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}});
    g.j["meshes"][0]["primitives"][0]["material"] = 0;
    g.scene({g.node({{"mesh", 0}})});
    const std::string path = g.writeGltf(dir, "i");
    EXPECT_EQ(errorOf(rg::loadGltf(path)),
              "'" + path + "': image 0 'missing.png': cannot open '" + dir + "/missing.png': No such file or directory");
    writeText(dir + "/missing.png", "not a png");
    EXPECT_EQ(errorOf(rg::loadGltf(path)).rfind("'" + path + "': image 0 'missing.png': not a PNG or JPEG image (", 0), 0u)
        << errorOf(rg::loadGltf(path));
    // Without loading images, the reference stays and nothing is opened.
    rg::GltfOptions o;
    o.loadImages = false;
    auto lazy = rg::loadGltf(path, o);
    ASSERT_TRUE(lazy) << errorOf(lazy);
    EXPECT_EQ(lazy->materials[0].baseColorTex.image, 0);
    EXPECT_EQ(lazy->images[0].pixels.width, 0u);
}

TEST(GltfErrors, AccessorAndBufferViewOutOfRange) {
    const std::string dir = tmpDir("range");
    GltfBuilder g;
    const std::vector<float> pos = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const int view = g.view(pos.data(), 24);  // two vertices' worth...
    g.bin.resize(36);
    g.accessor(view, kFloat, 3, "VEC3");      // ...read as three
    g.mesh("tri", json::array({{{"attributes", {{"POSITION", 0}}}}}));
    g.scene({g.node({{"mesh", 0}})});
    const std::string path = g.writeGltf(dir, "r");
    EXPECT_EQ(errorOf(rg::loadGltf(path)), "'" + path +
                                               "': mesh 0 'tri' primitive 0: POSITION: accessor 0 is out of range: it reads bytes "
                                               "0..36 of buffer view 0, which has 24 bytes");
    // A buffer view past the end of its buffer.
    g.j["bufferViews"][0]["byteLength"] = 36;
    g.j["bufferViews"][0]["byteOffset"] = 8;
    EXPECT_EQ(errorOf(rg::loadGltf(g.writeGltf(dir, "r2"))),
              "'" + dir + "/r2.gltf': mesh 0 'tri' primitive 0: POSITION: accessor 0: buffer view 0 (bytes 8..44) is outside buffer 0 (36 bytes)");
    // An accessor index that does not exist.
    g.j["bufferViews"][0]["byteOffset"] = 0;
    g.j["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] = 7;
    EXPECT_EQ(errorOf(rg::loadGltf(g.writeGltf(dir, "r3"))),
              "'" + dir + "/r3.gltf': mesh 0 'tri' primitive 0: NORMAL: accessor 7 does not exist (1 accessors)");
    // A wrong accessor type.
    g.j["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] = 0;
    g.j["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] = 0;
    EXPECT_EQ(errorOf(rg::loadGltf(g.writeGltf(dir, "r4"))),
              "'" + dir + "/r4.gltf': mesh 0 'tri' primitive 0: TEXCOORD_0: accessor 0 is VEC3, expected VEC2");
}

TEST(GltfErrors, IndexOutOfRange) {
    const std::string dir = tmpDir("index");
    GltfBuilder g;
    const int pos = g.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
    const int idx = g.indices16({0, 1, 5});
    g.mesh("tri", json::array({{{"attributes", {{"POSITION", pos}}}, {"indices", idx}}}));
    g.scene({g.node({{"mesh", 0}})});
    const std::string path = g.writeGltf(dir, "i");
    EXPECT_EQ(errorOf(rg::loadGltf(path)), "'" + path +
                                               "': mesh 0 'tri' primitive 0: indices: accessor 1: index 5 (element 2) is out of range: "
                                               "the primitive has 3 vertices");
}

TEST(GltfErrors, UnsupportedPrimitiveMode) {
    const std::string dir = tmpDir("mode");
    GltfBuilder g;
    const int pos = g.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
    g.mesh("pts", json::array({{{"attributes", {{"POSITION", pos}}}, {"mode", 0}}}));
    g.scene({g.node({{"mesh", 0}})});
    const std::string path = g.writeGltf(dir, "m");
    auto r = rg::loadGltf(path);
    ASSERT_FALSE(r);
    EXPECT_EQ(r.error().code, ErrorCode::Unsupported);
    EXPECT_EQ(r.error().message, "'" + path + "': mesh 0 'pts' primitive 0: mode POINTS is not supported (only triangles)");
    g.j["meshes"][0]["primitives"][0]["mode"] = 3;
    EXPECT_EQ(errorOf(rg::loadGltf(g.writeGltf(dir, "m2"))),
              "'" + dir + "/m2.gltf': mesh 0 'pts' primitive 0: mode LINE_STRIP is not supported (only triangles)");
    g.j["meshes"][0]["primitives"][0].erase("mode");
    g.j["meshes"][0]["primitives"][0]["attributes"].erase("POSITION");
    g.j["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] = pos;
    EXPECT_EQ(errorOf(rg::loadGltf(g.writeGltf(dir, "m3"))), "'" + dir + "/m3.gltf': mesh 0 'pts' primitive 0: no POSITION attribute");
}

TEST(GltfErrors, NumbersOutsideTheirGltfRange) {
    const std::string dir = tmpDir("numbers");
    GltfBuilder g;
    g.j["materials"] = json::array({{{"name", "m"}, {"pbrMetallicRoughness", {{"roughnessFactor", 1.5}}}}});
    EXPECT_EQ(errorOf(rg::loadGltf(g.writeGltf(dir, "a"))), "'" + dir + "/a.gltf': material 0 'm': roughnessFactor is 1.5, expected a number in [0, 1]");
    g.j["materials"] = json::array({{{"emissiveFactor", {1, 2, 0}}}});
    EXPECT_EQ(errorOf(rg::loadGltf(g.writeGltf(dir, "b"))), "'" + dir + "/b.gltf': material 0: emissiveFactor[1] is 2, expected a number in [0, 1]");
    g.j.erase("materials");
    g.j["extensions"]["KHR_lights_punctual"]["lights"] =
        json::array({{{"type", "spot"}, {"intensity", 1.0}, {"spot", {{"innerConeAngle", 0.9}, {"outerConeAngle", 0.5}}}}});
    g.scene({g.node({{"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}})});
    EXPECT_EQ(errorOf(rg::loadGltf(g.writeGltf(dir, "c"))), "'" + dir + "/c.gltf': light 0: spot.innerConeAngle is 0.9, expected a number in [0, 0.5]");
}

TEST(GltfErrors, NodeCycleAndBadTransforms) {
    const std::string dir = tmpDir("cycle");
    GltfBuilder g;
    g.node({{"name", "a"}, {"children", {1}}});
    g.node({{"name", "b"}, {"children", {0}}});
    g.scene({0});
    EXPECT_EQ(errorOf(rg::loadGltf(g.writeGltf(dir, "c"))),
              "'" + dir + "/c.gltf': node 0 'a' is its own ancestor (the node hierarchy has a cycle)");
    // A node shared by two parents.
    GltfBuilder d;
    const int shared = d.node({{"name", "s"}});
    d.scene({d.node({{"children", {shared}}}), d.node({{"children", {shared}}})});
    EXPECT_EQ(errorOf(rg::loadGltf(d.writeGltf(dir, "d"))),
              "'" + dir + "/d.gltf': node 0 's' appears twice in the hierarchy (a glTF node has one parent)");
    // A chain too deep to walk.
    GltfBuilder deep;
    for (int i = 0; i < 1100; ++i) deep.node(i + 1 < 1100 ? json{{"children", {i + 1}}} : json::object());
    deep.scene({0});
    EXPECT_EQ(errorOf(rg::loadGltf(deep.writeGltf(dir, "deep"))), "'" + dir + "/deep.gltf': the node hierarchy is deeper than 1000 levels");
    GltfBuilder h;
    h.scene({h.node({{"name", "n"}, {"rotation", {0, 0, 1}}})});
    EXPECT_EQ(errorOf(rg::loadGltf(h.writeGltf(dir, "r"))), "'" + dir + "/r.gltf': node 0 'n': rotation has 3 values, expected 4");
}

// ---------------------------------------------------------------------------------------------
// Mips

TEST(Mips, ChainSizesDownToOneByOne) {
    rg::SceneImage img;
    img.pixels = rg::Image(5, 3, 4);
    rg::generateMips(img);
    ASSERT_EQ(img.mipLevels, 3u);
    ASSERT_EQ(img.mips.size(), 2u);
    EXPECT_EQ(img.level(1).width, 2u);
    EXPECT_EQ(img.level(1).height, 1u);
    EXPECT_EQ(img.level(2).width, 1u);
    EXPECT_EQ(img.level(2).height, 1u);
    rg::SceneImage tall;
    tall.pixels = rg::Image(1, 16, 1);
    rg::generateMips(tall);
    EXPECT_EQ(tall.mipLevels, 5u);
    EXPECT_EQ(tall.level(4).height, 1u);
}

TEST(Mips, BoxFilterAveragesAreaWeighted) {
    // 4x4 ramp: level 1 texels are 2x2 means, level 2 the mean of all.
    rg::SceneImage img;
    img.pixels = rg::Image(4, 4, 1);
    for (uint32_t i = 0; i < 16; ++i) img.pixels.pixels[i] = float(i);
    rg::generateMips(img);
    EXPECT_FLOAT_EQ(img.level(1).at(0, 0, 0), (0 + 1 + 4 + 5) / 4.0f);
    EXPECT_FLOAT_EQ(img.level(1).at(1, 1, 0), (10 + 11 + 14 + 15) / 4.0f);
    EXPECT_FLOAT_EQ(img.level(2).at(0, 0, 0), 7.5f);
    // Odd width: 3 -> 1 covers all three texels equally (no texel dropped).
    rg::SceneImage odd;
    odd.pixels = rg::Image(3, 1, 1);
    odd.pixels.pixels = {0, 3, 9};
    rg::generateMips(odd);
    EXPECT_FLOAT_EQ(odd.level(1).at(0, 0, 0), 4.0f);
}

TEST(Mips, SrgbImagesAreFilteredAsLinearLightAlphaStaysLinear) {
    rg::SceneImage img;
    img.srgb = true;
    img.pixels = rg::Image(2, 2, 4);
    for (uint32_t y = 0; y < 2; ++y)
        for (uint32_t x = 0; x < 2; ++x) {
            const float v = (x + y) % 2 ? 1.0f : 0.0f;  // checkerboard black / white
            for (uint32_t c = 0; c < 3; ++c) img.pixels.at(x, y, c) = v;
            img.pixels.at(x, y, 3) = v;
        }
    rg::generateMips(img);
    // Half the light: srgbEncode(0.5) = 0.735, not the code-value mean 0.5.
    EXPECT_NEAR(img.level(1).at(0, 0, 0), 0.7353569f, 1e-5f);
    EXPECT_FLOAT_EQ(img.level(1).at(0, 0, 3), 0.5f);
}

// ---------------------------------------------------------------------------------------------
// Generated meshes

void checkMesh(const rg::Primitive& p, const std::string& what) {
    ASSERT_FALSE(p.indices.empty()) << what;
    for (size_t t = 0; t < p.indices.size(); t += 3) {
        const rg::Vertex &a = p.vertices[p.indices[t]], &b = p.vertices[p.indices[t + 1]], &c = p.vertices[p.indices[t + 2]];
        const glm::vec3 face = glm::cross(b.position - a.position, c.position - a.position);
        ASSERT_GT(glm::length(face), 0.0f) << what << " degenerate triangle " << t / 3;
        // Counter-clockwise seen from the side the normals point to.
        EXPECT_GT(glm::dot(face, a.normal + b.normal + c.normal), 0.0f) << what << " triangle " << t / 3;
    }
    // The analytic tangents agree with what generateTangents derives from the uvs.
    rg::Primitive derived = p;
    rg::generateTangents(derived);
    for (size_t i = 0; i < p.vertices.size(); ++i) {
        const rg::Vertex& v = p.vertices[i];
        EXPECT_NEAR(glm::length(v.normal), 1.0f, 1e-5f) << what;
        EXPECT_NEAR(glm::dot(glm::vec3(v.tangent), v.normal), 0.0f, 1e-5f) << what;
        EXPECT_EQ(v.tangent.w, derived.vertices[i].tangent.w) << what << " vertex " << i;
        // Pole vertices of a sphere have no uv gradient of their own: only compare away from them.
        if (std::fabs(v.normal.y) < 0.99f) {
            EXPECT_GT(glm::dot(glm::vec3(v.tangent), glm::vec3(derived.vertices[i].tangent)), 0.95f) << what << " vertex " << i;
        }
    }
}

TEST(Meshes, SpherePlaneAndBoxAreClosedCcwAndTheirTangentsMatchTheUvs) {
    auto sphere = rg::makeSphere(0.5f, 16, 0);
    EXPECT_EQ(sphere.vertices.size(), 17u * 9u);
    EXPECT_EQ(sphere.indices.size(), (16u * 8u * 2u - 2u * 16u) * 3u);
    for (const auto& v : sphere.vertices) EXPECT_NEAR(glm::length(v.position), 0.5f, 1e-6f);
    checkMesh(sphere, "sphere");
    checkMesh(rg::makePlane(2, 3, 0), "plane");
    checkMesh(rg::makeBox({1, 2, 3}, 0), "box");
    auto box = rg::makeBox({1, 2, 3}, 0);
    glm::vec3 lo(1e9f), hi(-1e9f);
    for (const auto& v : box.vertices) lo = glm::min(lo, v.position), hi = glm::max(hi, v.position);
    expectNear(lo, {-0.5f, -1, -1.5f}, 0, "box min");
    expectNear(hi, {0.5f, 1, 1.5f}, 0, "box max");
}

// ---------------------------------------------------------------------------------------------
// Lua scene scripts

std::string scenePath(const std::string& name) { return std::string(RG_SOURCE_ROOT) + "/scripts/scenes/" + name; }

TEST(SceneScript, DefaultSceneLoads) {
    auto scene = rg::loadSceneScript(scenePath("default.lua"));
    ASSERT_TRUE(scene) << errorOf(scene);
    int spheres = 0;
    for (const auto& n : scene->nodes) spheres += n.name.rfind("sphere_", 0) == 0;
    EXPECT_EQ(spheres, 49);
    EXPECT_EQ(scene->nodes.size(), 49u + 4u);  // + floor, crate, pillar, panel
    EXPECT_EQ(scene->meshes.size(), scene->nodes.size());
    // Smoothness 0..1 along +x, metal 0..1 along +z.
    const auto find = [&](const std::string& name) -> const rg::Node& {
        for (const auto& n : scene->nodes)
            if (n.name == name) return n;
        throw std::runtime_error("no node " + name);
    };
    const rg::Node& corner = find("sphere_6_0");
    const rg::Material& m = scene->materials[scene->meshes[size_t(corner.mesh)].primitives[0].material];
    EXPECT_FLOAT_EQ(m.smoothness, 1.0f);
    EXPECT_FLOAT_EQ(m.metalMask, 0.0f);
    EXPECT_GT(origin(corner.world).x, origin(find("sphere_0_0").world).x);
    EXPECT_GT(origin(find("sphere_0_6").world).z, origin(find("sphere_0_0").world).z);
    ASSERT_EQ(scene->lights.size(), 2u);
    EXPECT_EQ(scene->lights[0].type, rg::LightType::Directional);
    EXPECT_EQ(scene->lights[0].unit, "lux");
    EXPECT_EQ(scene->lights[1].unit, "lm");
    ASSERT_EQ(scene->cameras.size(), 1u);
    EXPECT_EQ(scene->cameras[0].name, "main");
    EXPECT_FLOAT_EQ(scene->cameras[0].aperture, 8.0f);
    EXPECT_FLOAT_EQ(scene->cameras[0].shutter, 1.0f / 125.0f);
    ASSERT_TRUE(scene->environment);
    EXPECT_EQ(scene->environment->kind, "sky");
    EXPECT_EQ(scene->files.size(), 1u);
    EXPECT_EQ(fs::path(scene->files[0]).filename(), "default.lua");
    EXPECT_LT(scene->boundsMin.y, 0.001f);
    EXPECT_GT(scene->boundsMax.x, 3.0f);
}

TEST(SceneScript, MaterialsAndFurnaceScenesLoadWithTheirParameters) {
    auto scene = rg::loadSceneScript(scenePath("materials.lua"));
    ASSERT_TRUE(scene) << errorOf(scene);
    auto material = [&](const std::string& name) -> const rg::Material& {
        for (const auto& m : scene->materials)
            if (m.name == name) return m;
        throw std::runtime_error("no material " + name);
    };
    EXPECT_EQ(material("rust").model, "two_colour");
    EXPECT_EQ(material("rust").f0, glm::vec3(0.35f, 0.25f, 0.2f));
    EXPECT_EQ(material("rust").diffuseColor, glm::vec3(0.30f, 0.12f, 0.05f));
    EXPECT_EQ(material("car_paint").model, "clear_coat");
    EXPECT_EQ(material("car_paint").extra["coatSmoothness"].asNumber(), 0.95);
    EXPECT_EQ(material("sign").emissive, glm::vec3(500, 250, 50));
    EXPECT_EQ(material("glass").alphaMode, rg::AlphaMode::Blend);
    EXPECT_FLOAT_EQ(material("glass").opacity, 0.3f);
    EXPECT_TRUE(material("glass").doubleSided);
    EXPECT_FLOAT_EQ(material("chalk").reflectance, 0.35f);
    ASSERT_EQ(scene->lights.size(), 3u);
    EXPECT_EQ(scene->lights[2].type, rg::LightType::Rect);
    EXPECT_EQ(scene->lights[2].unit, "nits");
    expectNear(scene->lights[2].direction, glm::normalize(glm::vec3(0, -2.5f, 2)), 1e-6f, "rect aims at its target");

    auto furnace = rg::loadSceneScript(scenePath("furnace.lua"));
    ASSERT_TRUE(furnace) << errorOf(furnace);
    EXPECT_TRUE(furnace->lights.empty());
    ASSERT_TRUE(furnace->environment);
    EXPECT_EQ(furnace->environment->kind, "color");
    EXPECT_EQ(furnace->environment->color, glm::vec3(1.0f));
    EXPECT_EQ(furnace->materials.at(0).baseColor, glm::vec3(1.0f));
}

// Runs a scene script written into a temp folder that is also the project root, so origins
// read "<name>.lua:<line>".
struct ScriptRunner {
    std::string dir;
    explicit ScriptRunner(const std::string& name) : dir(tmpDir("lua_" + name)) {}
    rg::Result<rg::Scene> run(const std::string& file, const std::string& text) {
        writeText(dir + "/" + file, text);
        rg::SceneScriptOptions o;
        o.projectRoot = dir;
        return rg::loadSceneScript(dir + "/" + file, o);
    }
    std::string error(const std::string& text) { return errorOf(run("bad.lua", text)); }
};

TEST(SceneScript, ObjectFieldErrors) {
    ScriptRunner lua("objects");
    EXPECT_EQ(lua.error("scene.sphere \"ball\" { radius = -1 }"), "bad.lua:1: scene.sphere.ball.radius: expected a number > 0, got -1");
    EXPECT_EQ(lua.error("scene.sphere \"ball\" { radius = \"big\" }"),
              "bad.lua:1: scene.sphere.ball.radius: expected a number > 0, got \"big\"");
    EXPECT_EQ(lua.error("\nscene.sphere \"ball\" { radus = 1 }"),
              "bad.lua:2: scene.sphere.ball.radus: unknown field (did you mean 'radius'?); expected one of: 'position', 'rotation', "
              "'scale', 'material', 'cast_shadows', 'doc', 'radius', 'segments'");
    EXPECT_EQ(lua.error("scene.sphere \"ball\" { segments = 2.5 }"),
              "bad.lua:1: scene.sphere.ball.segments: expected a whole number in [3, 1024], got 2.5");
    EXPECT_EQ(lua.error("scene.box \"b\" { size = { 1, 0, 1 } }"),
              "bad.lua:1: scene.box.b.size: expected {x, y, z} in metres with each value > 0, got {1, 0, 1}");
    EXPECT_EQ(lua.error("scene.plane \"p\" { size = 3 }"),
              "bad.lua:1: scene.plane.p.size: expected {width, depth} in metres with each value > 0, got 3");
    EXPECT_EQ(lua.error("scene.box \"b\" { position = { 1, 2 } }"),
              "bad.lua:1: scene.box.b.position: expected {x, y, z} (3 numbers), got {1, 2}");
    EXPECT_EQ(lua.error("scene.box \"b\" { scale = 0 }"),
              "bad.lua:1: scene.box.b.scale: expected a number > 0 or {x, y, z} of numbers > 0, got 0");
    EXPECT_EQ(lua.error("scene.material \"red\" {}\nscene.sphere \"ball\" { material = \"redd\" }"),
              "bad.lua:2: scene.sphere.ball.material: unknown material 'redd' (did you mean 'red'?); declared: 'red'");
    EXPECT_EQ(lua.error("scene.sphere \"ball\" { material = \"red\" }"),
              "bad.lua:1: scene.sphere.ball.material: unknown material 'red'; the scene declares no scene.material");
    EXPECT_EQ(lua.error("scene.sphere \"a\" {}\nscene.box \"a\" {}"),
              "bad.lua:2: scene.box.a: scene.sphere 'a' is already declared (at bad.lua:1)");
    EXPECT_EQ(lua.error("scene.sphere \"a\" { 1, radius = 2 }"),
              "bad.lua:1: scene.sphere.a: unexpected positional value 1; expected named fields: 'position', 'rotation', 'scale', "
              "'material', 'cast_shadows', 'doc', 'radius', 'segments'");
    EXPECT_EQ(lua.error("scene.box \"b\" { cast_shadows = 0 }"), "bad.lua:1: scene.box.b.cast_shadows: expected a boolean, got 0");
    EXPECT_EQ(lua.error("scene.sphere \"a\" { 1, 2 }"), "bad.lua:1: scene.sphere.a: expected a table of fields after scene.sphere \"a\", got {1, 2}");
    EXPECT_EQ(lua.error("rg.pass \"gbuffer\" {}"), "bad.lua:1: rg.pass \"gbuffer\" belongs in a pipeline script, not in a scene");
    EXPECT_EQ(lua.error("scene.gltf \"g\" { file = \"nope.glb\" }"),
              "bad.lua:1: scene.gltf.g.file: cannot open '" + lua.dir + "/nope.glb': No such file or directory");
    EXPECT_EQ(lua.error("scene.gltf \"g\" {}"), "bad.lua:1: scene.gltf.g.file: missing (expected a .gltf or .glb file, relative to the script)");
}

TEST(SceneScript, MaterialFieldErrors) {
    ScriptRunner lua("materials");
    EXPECT_EQ(lua.error("scene.material \"red\" { base_color = { 1, 2, 0 } }"),
              "bad.lua:1: scene.material.red.base_color: expected {r, g, b} with each value in [0, 1], got {1, 2, 0}");
    EXPECT_EQ(lua.error("scene.material \"red\" { smoothness = 1.5 }"),
              "bad.lua:1: scene.material.red.smoothness: expected a number in [0, 1], got 1.5");
    EXPECT_EQ(lua.error("scene.material \"red\" { emissive = { -1, 0, 0 } }"),
              "bad.lua:1: scene.material.red.emissive: expected {r, g, b} with each value >= 0, got {-1, 0, 0}");
    EXPECT_EQ(lua.error("scene.material \"red\" { alpha = \"opaq\" }"),
              "bad.lua:1: scene.material.red.alpha: unknown alpha mode 'opaq' (did you mean 'opaque'?); expected one of: 'opaque', "
              "'mask', 'blend'");
    EXPECT_EQ(lua.error("scene.material \"red\" { alpha_cutoff = 0.5 }"),
              "bad.lua:1: scene.material.red.alpha_cutoff: applies to alpha = \"mask\" only");
    EXPECT_EQ(lua.error("scene.material \"red\" { f0 = { 0.5, 0.5, 0.5 } }"),
              "bad.lua:1: scene.material.red.f0: applies to model 'two_colour' only (this material's model is 'standard')");
    EXPECT_EQ(lua.error("scene.material \"rust\" { model = \"two_colour\", base_color = { 1, 0, 0 } }"),
              "bad.lua:1: scene.material.rust.base_color: not used by model 'two_colour', which takes diffuse_color and f0");
    EXPECT_EQ(lua.error("scene.material \"red\" { params = 3 }"),
              "bad.lua:1: scene.material.red.params: expected a table of named parameters, got 3");
    EXPECT_EQ(lua.error("scene.material \"red\" { double_sided = 1 }"),
              "bad.lua:1: scene.material.red.double_sided: expected a boolean, got 1");
    EXPECT_EQ(lua.error("scene.material \"red\" { metalness = 1 }"),
              "bad.lua:1: scene.material.red.metalness: unknown field; expected one of: 'model', 'base_color', 'smoothness', "
              "'metal_mask', 'reflectance', 'ao', 'emissive', 'opacity', 'diffuse_color', 'f0', 'params', 'double_sided', 'alpha', "
              "'alpha_cutoff', 'base_color_map', 'metallic_roughness_map', 'normal_map', 'normal_scale', 'occlusion_map', "
              "'emissive_map', 'doc'");
}

TEST(SceneScript, MaterialTextureFiles) {
    // The five glTF maps from files next to the script: decoded once per file and encoding,
    // base colour and emissive sRGB, the others linear; errors name the field and the file.
    ScriptRunner lua("textures");
    rg::Image checker(2, 2, 3);
    for (uint32_t y = 0; y < 2; ++y)
        for (uint32_t x = 0; x < 2; ++x)
            for (uint32_t c = 0; c < 3; ++c) checker.at(x, y, c) = (x + y) % 2 ? 1.0f : (c == 0 ? 0.8f : 0.2f);
    ASSERT_TRUE(rg::writePng(lua.dir + "/checker.png", checker));
    writeText(lua.dir + "/broken.png", "not a png");
    auto ok = lua.run("ok.lua",
                      "scene.material \"tiles\" { base_color_map = \"checker.png\", normal_map = \"checker.png\", normal_scale = 0.5,\n"
                      "                           emissive_map = \"checker.png\", emissive = { 1, 1, 1 } }\n"
                      "scene.material \"more\" { base_color_map = \"checker.png\", occlusion_map = \"checker.png\" }\n"
                      "scene.plane \"floor\" { size = { 2, 2 }, material = \"tiles\" }\n");
    ASSERT_TRUE(ok) << errorOf(ok);
    const rg::Material& tiles = ok->materials[0];
    ASSERT_TRUE(tiles.baseColorTex.valid());
    ASSERT_TRUE(tiles.normalTex.valid());
    EXPECT_FALSE(tiles.metallicRoughnessTex.valid());
    EXPECT_FLOAT_EQ(tiles.normalScale, 0.5f);
    // One sRGB and one linear decode of checker.png, shared by both materials.
    ASSERT_EQ(ok->images.size(), 2u);
    EXPECT_EQ(tiles.baseColorTex.image, ok->materials[1].baseColorTex.image);
    EXPECT_EQ(tiles.emissiveTex.image, tiles.baseColorTex.image);
    EXPECT_EQ(tiles.normalTex.image, ok->materials[1].occlusionTex.image);
    EXPECT_TRUE(ok->images[static_cast<size_t>(tiles.baseColorTex.image)].srgb);
    EXPECT_FALSE(ok->images[static_cast<size_t>(tiles.normalTex.image)].srgb);
    const rg::Image& px = ok->images[static_cast<size_t>(tiles.baseColorTex.image)].pixels;
    EXPECT_NEAR(px.at(0, 0, 0), 204.0f / 255.0f, 1e-6f);  // the file's 8-bit value, as stored
    EXPECT_EQ(px.at(1, 0, 1), 1.0f);
    EXPECT_GE(ok->files.size(), 2u);  // the script and the texture, for hot reload
    EXPECT_EQ(lua.error("scene.material \"m\" { base_color_map = \"nope.png\" }"),
              "bad.lua:1: scene.material.m.base_color_map: cannot open '" + lua.dir + "/nope.png': No such file or directory");
    EXPECT_EQ(lua.error("scene.material \"m\" { normal_map = \"broken.png\" }").rfind(
                  "bad.lua:1: scene.material.m.normal_map: cannot decode '" + lua.dir + "/broken.png': ", 0),
              0u);
    EXPECT_EQ(lua.error("scene.material \"m\" { normal_scale = 2 }"),
              "bad.lua:1: scene.material.m.normal_scale: applies with a normal_map only");
}

TEST(SceneScript, LightFieldErrorsAndUnitsPerType) {
    ScriptRunner lua("lights");
    EXPECT_EQ(lua.error("scene.light \"key\" { type = \"point\", intensity = 100, unit = \"lux\" }"),
              "bad.lua:1: scene.light.key.unit: a point light cannot be given in 'lux' (seed 000 tbl:8); expected 'lm', 'cd'");
    EXPECT_EQ(lua.error("scene.light \"sun\" { type = \"sun\", intensity = 100, unit = \"lm\", direction = { 0, -1, 0 } }"),
              "bad.lua:1: scene.light.sun.unit: a sun light cannot be given in 'lm' (seed 000 tbl:8); expected 'lux'");
    EXPECT_EQ(lua.error("scene.light \"a\" { type = \"sphere\", intensity = 100, unit = \"cd\", radius = 0.1 }"),
              "bad.lua:1: scene.light.a.unit: a sphere light cannot be given in 'cd' (seed 000 tbl:8); expected 'lm', 'nits', 'ev100'");
    EXPECT_EQ(lua.error("scene.light \"a\" { type = \"point\", intensity = 100, unit = \"lumen\" }"),
              "bad.lua:1: scene.light.a.unit: unknown unit 'lumen'; a point light takes 'lm', 'cd'");
    EXPECT_EQ(lua.error("scene.light \"a\" { type = \"pointt\", intensity = 1 }"),
              "bad.lua:1: scene.light.a.type: unknown light type 'pointt' (did you mean 'point'?); expected one of: 'point', 'spot', "
              "'sun', 'directional', 'sphere', 'disk', 'rect', 'tube'");
    EXPECT_EQ(lua.error("scene.light \"a\" { intensity = 1 }"),
              "bad.lua:1: scene.light.a.type: missing (expected one of: 'point', 'spot', 'sun', 'sphere', 'disk', 'rect', 'tube')");
    EXPECT_EQ(lua.error("scene.light \"a\" { type = \"point\" }"), "bad.lua:1: scene.light.a.intensity: missing (expected a number, in 'lm', 'cd')");
    EXPECT_EQ(lua.error("scene.light \"a\" { type = \"point\", intensity = -5 }"),
              "bad.lua:1: scene.light.a.intensity: expected a number >= 0, got -5");
    EXPECT_EQ(lua.error("scene.light \"a\" { type = \"point\", intensity = 5, color = { 1, 1, 1 }, temperature = 3000 }"),
              "bad.lua:1: scene.light.a.temperature: give either color or temperature, not both");
    EXPECT_EQ(lua.error("scene.light \"a\" { type = \"point\", intensity = 5, temperature = 1000 }"),
              "bad.lua:1: scene.light.a.temperature: expected a number in [1667, 25000], got 1000");
    EXPECT_EQ(lua.error("scene.light \"a\" { type = \"point\", intensity = 5, temperature = 3000, locus = \"daylight\" }"),
              "bad.lua:1: scene.light.a.temperature: expected a number in [4000, 25000], got 3000");
    EXPECT_EQ(lua.error("scene.light \"a\" { type = \"point\", intensity = 5, locus = \"daylight\" }"),
              "bad.lua:1: scene.light.a.locus: applies with a temperature only");
    EXPECT_EQ(lua.error("scene.light \"a\" { type = \"disk\", intensity = 5, radius = 0.1, direction = { 0, -1, 0 }, inner_angle = 10 }"),
              "bad.lua:1: scene.light.a.inner_angle: a disk's cone needs its outer_angle too (seed 000 lst:9)");
    EXPECT_EQ(lua.error("scene.light \"a\" { type = \"point\", intensity = 5, width = 1 }"),
              "bad.lua:1: scene.light.a.width: not used by a point light (only by rect lights)");
    EXPECT_EQ(lua.error("scene.light \"s\" { type = \"sun\", intensity = 5, direction = { 0, -1, 0 }, range = 3 }"),
              "bad.lua:1: scene.light.s.range: not used by a sun light (only by local lights)");
    EXPECT_EQ(lua.error("scene.light \"s\" { type = \"sun\", intensity = 5, direction = { 0, -1, 0 }, shadow = true }"),
              "bad.lua:1: scene.light.s.shadow: not used by a sun light (only by local lights; the sun's shadow is the pipeline's sun_shadows parameter)");
    EXPECT_EQ(lua.error("scene.light \"a\" { type = \"point\", intensity = 5, shadow = 1 }"),
              "bad.lua:1: scene.light.a.shadow: expected a boolean, got 1");
    EXPECT_EQ(lua.error("scene.light \"a\" { type = \"spot\", intensity = 5 }"),
              "bad.lua:1: scene.light.a.direction: missing (a spot light needs direction or target)");
    EXPECT_EQ(lua.error("scene.light \"a\" { type = \"spot\", intensity = 5, direction = { 0, -1, 0 }, inner_angle = 40, outer_angle = 30 }"),
              "bad.lua:1: scene.light.a.inner_angle: is 40°, wider than outer_angle (30°)");
    EXPECT_EQ(lua.error("scene.light \"a\" { type = \"rect\", intensity = 5, direction = { 0, -1, 0 }, width = 1 }"),
              "bad.lua:1: scene.light.a.height: missing (a rect light needs its height in metres)");
    EXPECT_EQ(lua.error("scene.light \"a\" { type = \"tube\", intensity = 5, unit = \"ev100\", direction = { 1, 0, 0 }, radius = 0.02 }"),
              "bad.lua:1: scene.light.a.length: missing (a tube light needs its length in metres)");
    EXPECT_EQ(lua.error("scene.light \"a\" { type = \"point\", intensity = 5, ies = \"x.ies\" }"),
              "bad.lua:1: scene.light.a.ies: cannot open '" + lua.dir + "/x.ies': No such file or directory");
    EXPECT_EQ(lua.error("scene.light \"a\" { type = \"point\", intensity = 5, exact_cone = true }"),
              "bad.lua:1: scene.light.a.exact_cone: not used by a point light (only by spot lights)");
    EXPECT_EQ(lua.error("scene.light \"a\" { type = \"point\", intensity = 5, ies_mode = \"mask\" }"),
              "bad.lua:1: scene.light.a.ies_mode: needs an ies profile to apply");
    EXPECT_EQ(lua.error("scene.light \"a\" { type = \"sphere\", intensity = 5, radius = 1, ies_mode = \"mask\" }"),
              "bad.lua:1: scene.light.a.ies_mode: not used by a sphere light (only by point and spot lights with an IES profile)");
    // Valid: EV100 may be negative; spot angles are degrees, stored in radians.
    auto ok = lua.run("ok.lua",
                      "scene.light \"a\" { type = \"disk\", intensity = -2, unit = \"ev100\", radius = 0.5, target = { 0, 0, 0 }, position = { 0, 2, 0 } }\n"
                      "scene.light \"b\" { type = \"spot\", intensity = 800, direction = { 0, -1, 0 }, inner_angle = 20, outer_angle = 30,\n"
                      "                   exact_cone = true }\n");
    ASSERT_TRUE(ok) << errorOf(ok);
    EXPECT_FALSE(ok->lights[0].exactCone);
    EXPECT_TRUE(ok->lights[1].exactCone);
    EXPECT_FLOAT_EQ(ok->lights[0].intensity, -2.0f);
    expectNear(ok->lights[0].direction, {0, -1, 0}, 1e-6f, "disk direction from target");
    EXPECT_EQ(ok->lights[1].unit, "lm");  // the default unit of a spot light
    EXPECT_NEAR(ok->lights[1].outerAngle, 30.0f * 3.14159265f / 180.0f, 1e-6f);
}

TEST(SceneScript, CameraAndEnvironmentFieldErrors) {
    ScriptRunner lua("camera");
    EXPECT_EQ(lua.error("scene.camera \"c\" { fov = 200 }"), "bad.lua:1: scene.camera.c.fov: expected a number in (0, 180), got 200");
    EXPECT_EQ(lua.error("scene.camera \"c\" { fov = 40, focal_length = 50 }"),
              "bad.lua:1: scene.camera.c.focal_length: give either fov or focal_length (with sensor_height), not both");
    EXPECT_EQ(lua.error("scene.camera \"c\" { position = { 0, 0, 0 }, target = { 0, 0, 0 } }"),
              "bad.lua:1: scene.camera.c.target: equals position; the camera needs a direction to look in");
    EXPECT_EQ(lua.error("scene.camera \"c\" { near = 10, far = 5 }"), "bad.lua:1: scene.camera.c.far: is 5, not beyond near (10)");
    EXPECT_EQ(lua.error("scene.camera \"c\" { position = { 0, 10, 0 } }"),
              "bad.lua:1: scene.camera.c.up: is parallel to the view direction (or zero); e.g. up = {0, 0, -1} for a camera looking straight down");
    EXPECT_EQ(lua.error("scene.camera \"c\" { aperture = 0 }"), "bad.lua:1: scene.camera.c.aperture: expected a number in [0.5, 128], got 0");
    EXPECT_EQ(lua.error("scene.camera \"c\" { height = 4, fov = 30 }"), "bad.lua:1: scene.camera.c.height: an orthographic camera (height) has no fov or focal_length");
    EXPECT_EQ(lua.error("scene.camera \"c\" { height = 0 }"), "bad.lua:1: scene.camera.c.height: expected a number > 0, got 0");
    EXPECT_EQ(lua.error("scene.environment \"e\" { kind = \"hdri\" }"),
              "bad.lua:1: scene.environment.e.kind: unknown environment kind 'hdri' (did you mean 'hdr'?); expected one of: 'sky', "
              "'hdr', 'color'");
    EXPECT_EQ(lua.error("scene.environment \"e\" { kind = \"hdr\", file = \"sky.hdr\" }"),
              "bad.lua:1: scene.environment.e.file: cannot open '" + lua.dir + "/sky.hdr': No such file or directory");
    EXPECT_EQ(lua.error("scene.environment \"e\" { kind = \"sky\", unit = \"lux\" }"),
              "bad.lua:1: scene.environment.e.unit: an environment's luminance is in 'nits' (seed 000 tbl:8), got 'lux'");
    EXPECT_EQ(lua.error("scene.environment \"z\" { kind = \"sky\" }\nscene.environment \"b\" { kind = \"sky\" }"),
              "bad.lua:2: scene.environment.b: a scene has one environment; 'z' is declared at bad.lua:1");
    // A Lua error and a missing script pass through with their position.
    EXPECT_EQ(lua.error("scene.sphere \"a\" {").rfind("bad.lua:1:", 0), 0u);
    auto missing = rg::loadSceneScript(lua.dir + "/none.lua");
    ASSERT_FALSE(missing);
    EXPECT_EQ(missing.error().code, ErrorCode::NotFound);
    EXPECT_EQ(missing.error().message, "scene script: cannot open '" + lua.dir + "/none.lua': No such file or directory");

    // Focal length and sensor height in millimetres give the vertical field of view.
    auto ok = lua.run("cam.lua", "scene.camera \"c\" { focal_length = 50, sensor_height = 24, aperture = 2.8, shutter = 0.01, iso = 400, ec = -1 }");
    ASSERT_TRUE(ok) << errorOf(ok);
    EXPECT_NEAR(ok->cameras[0].verticalFov, 2 * std::atan(12.0f / 50.0f), 1e-6f);
    EXPECT_FLOAT_EQ(ok->cameras[0].focalLength, 0.05f);
    EXPECT_FLOAT_EQ(ok->cameras[0].iso, 400.0f);
    EXPECT_FLOAT_EQ(ok->cameras[0].exposureCompensation, -1.0f);
}

TEST(SceneScript, ProbesAndTheirFieldErrors) {
    ScriptRunner lua("probes");
    // The README's example (scripts/scenes/README.md).
    auto ok = lua.run("probes.lua", "scene.probe \"room\" { shape = \"box\", position = { 0, 1.5, 0 }, size = { 8, 3, 6 }, fade = 0.5 }\n"
                                    "scene.probe \"alcove\" { position = { 3, 1, -2 }, radius = 1.5, influence = 2.5, priority = 1 }");
    ASSERT_TRUE(ok) << errorOf(ok);
    ASSERT_EQ(ok->probes.size(), 2u);
    EXPECT_TRUE(ok->probes[0].box);
    EXPECT_EQ(ok->probes[0].size, glm::vec3(8, 3, 6));
    EXPECT_FLOAT_EQ(ok->probes[0].fade, 0.5f);
    EXPECT_EQ(ok->probes[0].origin, "probes.lua:1");
    EXPECT_FALSE(ok->probes[1].box);
    EXPECT_FLOAT_EQ(ok->probes[1].radius, 1.5f);
    EXPECT_EQ(ok->probes[1].priority, 1);
    EXPECT_FLOAT_EQ(ok->probes[1].fade, 0.25f);
    EXPECT_FLOAT_EQ(ok->probes[1].influenceRadius, 2.5f);
    EXPECT_EQ(ok->probes[0].influenceSize, glm::vec3(0.0f));  // the proxy's
    auto wide = lua.run("wide.lua", "scene.probe \"s\" { radius = 1, influence = 3 }\n"
                                    "scene.probe \"b\" { shape = \"box\", size = { 1, 2, 3 }, influence = { 4, 5, 6 } }");
    ASSERT_TRUE(wide) << errorOf(wide);
    EXPECT_FLOAT_EQ(wide->probes[0].influenceRadius, 3.0f);
    EXPECT_EQ(wide->probes[1].influenceSize, glm::vec3(4, 5, 6));
    EXPECT_EQ(lua.error("scene.probe \"p\" { influence = 0 }"), "bad.lua:1: scene.probe.p.influence: expected a number > 0, got 0");
    EXPECT_EQ(lua.error("scene.probe \"p\" { size = { 1, 1, 1 } }"),
              "bad.lua:1: scene.probe.p.size: a sphere probe has a radius (give shape = \"box\" for a size)");
    EXPECT_EQ(lua.error("scene.probe \"p\" { shape = \"box\", radius = 2 }"), "bad.lua:1: scene.probe.p.radius: a box probe has a size, not a radius");
    EXPECT_EQ(lua.error("scene.probe \"p\" { shape = \"cone\" }"),
              "bad.lua:1: scene.probe.p.shape: unknown probe shape 'cone'; expected one of: 'sphere', 'box'");
    EXPECT_EQ(lua.error("scene.probe \"p\" { priority = 1.5 }"),
              "bad.lua:1: scene.probe.p.priority: expected a whole number in [-1000, 1000], got 1.5");
    EXPECT_EQ(lua.error("scene.probe \"p\" { radius = 0 }"), "bad.lua:1: scene.probe.p.radius: expected a number > 0, got 0");
    EXPECT_EQ(lua.error("for i = 1, 9 do scene.probe(\"p\" .. i) {} end"),
              "bad.lua:1: scene.probe.p9: a scene has at most 8 light probes (shaders/lib/probes.glsl RG_MAX_PROBES)");
}

TEST(SceneScript, DefaultCameraFramesTheBounds) {
    ScriptRunner lua("defcam");
    auto scene = lua.run("s.lua", "scene.box \"b\" { size = { 2, 2, 2 }, position = { 10, 1, 0 } }");
    ASSERT_TRUE(scene) << errorOf(scene);
    ASSERT_EQ(scene->cameras.size(), 1u);
    const rg::Camera& c = scene->cameras[0];
    EXPECT_EQ(c.name, "default");
    expectNear(c.target, {10, 1, 0}, 1e-5f, "looks at the centre");
    // Every corner of the bounds is inside the vertical field of view.
    const glm::vec3 fwd = glm::normalize(c.target - c.position);
    for (int k = 0; k < 8; ++k) {
        const glm::vec3 p((k & 1) ? scene->boundsMax.x : scene->boundsMin.x, (k & 2) ? scene->boundsMax.y : scene->boundsMin.y,
                          (k & 4) ? scene->boundsMax.z : scene->boundsMin.z);
        EXPECT_GT(glm::dot(glm::normalize(p - c.position), fwd), std::cos(c.verticalFov / 2)) << k;
    }
    // Objects without a material share a grey default one.
    EXPECT_EQ(scene->materials.size(), 1u);
    EXPECT_EQ(scene->materials[0].name, "default");
}

TEST(SceneScript, GltfIsMergedWithItsTransform) {
    ScriptRunner lua("merge");
    GltfBuilder g;
    addQuad(g, true);
    g.j["materials"] = json::array({{{"name", "paint"}, {"pbrMetallicRoughness", {{"roughnessFactor", 0.25}}}}});
    g.j["meshes"][0]["primitives"][0]["material"] = 0;
    g.j["extensions"]["KHR_lights_punctual"]["lights"] = json::array({{{"type", "point"}, {"intensity", 2.0}}});
    g.scene({g.node({{"name", "q"}, {"mesh", 0}, {"translation", {0, 1, 0}}}),
             g.node({{"name", "l"}, {"translation", {1, 0, 0}}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}})});
    fs::create_directories(lua.dir + "/models");
    g.writeGltf(lua.dir + "/models", "thing");
    auto scene = lua.run("s.lua",
                         "scene.material \"m\" {}\nscene.sphere \"s\" { material = \"m\" }\n"
                         "scene.gltf \"thing\" { file = \"models/thing.gltf\", position = { 10, 0, 0 }, rotation = { 0, 90, 0 }, scale = 2 }");
    ASSERT_TRUE(scene) << errorOf(scene);
    ASSERT_EQ(scene->nodes.size(), 2u);
    EXPECT_EQ(scene->nodes[1].name, "thing/q");
    expectNear(origin(scene->nodes[1].world), {10, 2, 0}, 1e-5f, "merged node");
    EXPECT_EQ(scene->nodes[1].mesh, 1);
    const auto& prim = scene->meshes[1].primitives[0];
    EXPECT_EQ(prim.material, 1u);
    EXPECT_EQ(scene->materials[1].name, "thing/paint");
    EXPECT_FLOAT_EQ(scene->materials[1].smoothness, 0.75f);
    ASSERT_EQ(scene->lights.size(), 1u);
    expectNear(scene->lights[0].position, {10, 0, -2}, 1e-5f, "light moved, turned and scaled with the model");
    EXPECT_EQ(scene->files.size(), 3u);  // the script, the .gltf and its .bin
}

// ---------------------------------------------------------------------------------------------
// exportGlb round trip

TEST(ExportGlb, LuaSceneRoundTripsThroughGlb) {
    auto scene = rg::loadSceneScript(scenePath("materials.lua"));
    ASSERT_TRUE(scene) << errorOf(scene);
    const std::string path = tmpDir("export") + "/materials.glb";
    std::vector<std::string> warnings;
    auto w = rg::exportGlb(*scene, path, &warnings);
    ASSERT_TRUE(w) << w.error().message;
    // The rect light has no glTF form; the sun (lux) and the bulb (cd) do.
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_EQ(warnings[0], "light 'softbox' (rect, nits) is not exported: KHR_lights_punctual has no area lights");

    auto back = rg::loadGltf(path);
    ASSERT_TRUE(back) << errorOf(back);
    ASSERT_EQ(back->meshes.size(), scene->meshes.size());
    for (size_t m = 0; m < scene->meshes.size(); ++m) {
        EXPECT_EQ(back->meshes[m].name, scene->meshes[m].name);
        ASSERT_EQ(back->meshes[m].primitives.size(), scene->meshes[m].primitives.size());
        for (size_t p = 0; p < scene->meshes[m].primitives.size(); ++p) {
            const auto &a = scene->meshes[m].primitives[p], &b = back->meshes[m].primitives[p];
            EXPECT_EQ(a.indices, b.indices);
            EXPECT_EQ(a.material, b.material);
            ASSERT_EQ(a.vertices.size(), b.vertices.size());
            for (size_t i = 0; i < a.vertices.size(); ++i) {
                EXPECT_EQ(a.vertices[i].position, b.vertices[i].position);
                EXPECT_EQ(a.vertices[i].normal, b.vertices[i].normal);
                EXPECT_EQ(a.vertices[i].tangent, b.vertices[i].tangent);
                EXPECT_EQ(a.vertices[i].uv0, b.vertices[i].uv0);
                EXPECT_EQ(a.vertices[i].uv1, b.vertices[i].uv1);
            }
        }
    }
    ASSERT_EQ(back->nodes.size(), scene->nodes.size());
    for (size_t n = 0; n < scene->nodes.size(); ++n) {
        EXPECT_EQ(back->nodes[n].name, scene->nodes[n].name);
        EXPECT_EQ(back->nodes[n].mesh, scene->nodes[n].mesh);
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r) EXPECT_FLOAT_EQ(back->nodes[n].world[c][r], scene->nodes[n].world[c][r]);
    }
    ASSERT_EQ(back->materials.size(), scene->materials.size());
    for (size_t i = 0; i < scene->materials.size(); ++i) {
        const rg::Material &a = scene->materials[i], &b = back->materials[i];
        SCOPED_TRACE(a.name);
        EXPECT_EQ(a.name, b.name);
        EXPECT_EQ(a.model, b.model);
        expectNear(a.baseColor, b.baseColor, 1e-7f, "baseColor");
        EXPECT_NEAR(a.smoothness, b.smoothness, 1e-7f);
        EXPECT_NEAR(a.metalMask, b.metalMask, 1e-7f);
        EXPECT_NEAR(a.reflectance, b.reflectance, 1e-7f);
        EXPECT_NEAR(a.ao, b.ao, 1e-7f);
        EXPECT_NEAR(a.opacity, b.opacity, 1e-7f);
        expectNear(a.emissive, b.emissive, 1e-4f, "emissive (nits, through emissive_strength)");
        expectNear(a.diffuseColor, b.diffuseColor, 1e-7f, "diffuseColor");
        expectNear(a.f0, b.f0, 1e-7f, "f0");
        EXPECT_EQ(a.alphaMode, b.alphaMode);
        EXPECT_EQ(a.doubleSided, b.doubleSided);
        EXPECT_EQ(a.extra, b.extra);
    }
    ASSERT_EQ(back->lights.size(), 2u);
    EXPECT_EQ(back->lights[0].name, "sun");
    EXPECT_EQ(back->lights[0].unit, "lux");
    expectNear(back->lights[0].direction, scene->lights[0].direction, 1e-6f, "sun direction");
    EXPECT_EQ(back->lights[1].unit, "cd");
    expectNear(back->lights[1].position, scene->lights[1].position, 1e-6f, "bulb position");
    EXPECT_EQ(back->lights[1].color, scene->lights[1].color);
    ASSERT_EQ(back->cameras.size(), 1u);
    const rg::Camera &ca = scene->cameras[0], &cb = back->cameras[0];
    expectNear(cb.position, ca.position, 1e-6f, "camera position");
    expectNear(cb.target, ca.target, 1e-6f, "camera target");
    EXPECT_FLOAT_EQ(cb.verticalFov, ca.verticalFov);
    EXPECT_FLOAT_EQ(cb.aperture, ca.aperture);
    EXPECT_FLOAT_EQ(cb.shutter, ca.shutter);
    ASSERT_TRUE(back->environment);
    EXPECT_EQ(back->environment->kind, "sky");
    expectNear(back->boundsMin, scene->boundsMin, 1e-5f, "bounds");
}

TEST(ExportGlb, LumensBecomeTheCandelaRenderedAndComeBack) {
    // KHR_lights_punctual holds cd: a 1600 lm point light is written as 1600 / 4π cd (tbl:9, what
    // rgraph renders it with) and a 1000 lm spot as 1000 / π cd (eq:17); the declared lumens ride
    // in extras, so rgraph reads lumens back while other readers light it the same.
    rg::Scene scene;
    rg::Light point;
    point.name = "bulb";
    point.type = rg::LightType::Point;
    point.unit = "lm";
    point.intensity = 1600.0f;
    rg::Light spot = point;
    spot.name = "torch";
    spot.type = rg::LightType::Spot;
    spot.intensity = 1000.0f;
    spot.outerAngle = 0.5f;
    spot.innerAngle = 0.3f;
    rg::Light exact = spot;  // eq:16: the flux over the cone, 1000 / (2π (1 − cos 0.5)) cd
    exact.name = "beam";
    exact.exactCone = true;
    exact.castShadows = true;  // extras.rgraph.shadow
    scene.lights = {point, spot, exact};
    const std::string path = tmpDir("export_lumens") + "/lumens.glb";  // its own folder: tests run in parallel
    std::vector<std::string> warnings;
    auto w = rg::exportGlb(scene, path, &warnings);
    ASSERT_TRUE(w) << w.error().message;
    EXPECT_TRUE(warnings.empty());
    // The GLB's JSON chunk: 12-byte header, then chunk length, type, JSON.
    std::ifstream in(path, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    ASSERT_GT(bytes.size(), 20u);
    uint32_t jsonLength = 0;
    std::memcpy(&jsonLength, bytes.data() + 12, 4);
    const auto json = nlohmann::json::parse(bytes.substr(20, jsonLength));
    const auto& lights = json["extensions"]["KHR_lights_punctual"]["lights"];
    ASSERT_EQ(lights.size(), 3u);
    EXPECT_NEAR(lights[0]["intensity"].get<double>(), 1600.0 / (4.0 * 3.14159265358979), 1e-3);
    EXPECT_NEAR(lights[1]["intensity"].get<double>(), 1000.0 / 3.14159265358979, 1e-3);
    EXPECT_NEAR(lights[2]["intensity"].get<double>(), 1000.0 / (2.0 * 3.14159265358979 * (1.0 - std::cos(0.5))), 1e-2);
    auto back = rg::loadGltf(path);
    ASSERT_TRUE(back) << errorOf(back);
    ASSERT_EQ(back->lights.size(), 3u);
    EXPECT_FALSE(back->lights[1].exactCone);
    EXPECT_TRUE(back->lights[2].exactCone);
    EXPECT_FALSE(back->lights[1].castShadows);
    EXPECT_TRUE(back->lights[2].castShadows);
    EXPECT_EQ(back->lights[0].unit, "lm");
    EXPECT_FLOAT_EQ(back->lights[0].intensity, 1600.0f);
    EXPECT_EQ(back->lights[1].unit, "lm");
    EXPECT_FLOAT_EQ(back->lights[1].intensity, 1000.0f);
}

TEST(ExportGlb, TexturesSamplersAndTransformsRoundTrip) {
    const std::string dir = tmpDir("export_tex");
    writeTestPng(dir + "/a.png", 2, 2, {0, 0, 0, 1, 1, 1, 1, 1, 0.5f, 0.25f, 0.75f, 1, 1, 0, 0, 0.5f});
    GltfBuilder g;
    addQuad(g, true);
    g.j["images"] = json::array({{{"uri", "a.png"}}});
    g.j["samplers"] = json::array({{{"magFilter", 9728}, {"minFilter", 9986}, {"wrapS", 33648}}});
    g.j["textures"] = json::array({{{"source", 0}, {"sampler", 0}}});
    g.j["materials"] = json::array({{{"pbrMetallicRoughness",
                                      {{"baseColorTexture",
                                        {{"index", 0},
                                         {"extensions", {{"KHR_texture_transform", {{"offset", {0.1, 0.2}}, {"rotation", 0.3}, {"scale", {2, 4}}}}}}}}}},
                                     {"normalTexture", {{"index", 0}, {"texCoord", 1}}},
                                     {"alphaMode", "MASK"},
                                     {"alphaCutoff", 0.4}}});
    g.j["meshes"][0]["primitives"][0]["material"] = 0;
    g.scene({g.node({{"mesh", 0}})});
    auto scene = rg::loadGltf(g.writeGltf(dir, "t"));
    ASSERT_TRUE(scene) << errorOf(scene);
    ASSERT_TRUE(rg::exportGlb(*scene, dir + "/t.glb"));
    auto back = rg::loadGltf(dir + "/t.glb");
    ASSERT_TRUE(back) << errorOf(back);
    ASSERT_EQ(back->images.size(), 2u);  // one image, once as sRGB (base colour) and once linear (normal map)
    for (size_t i = 0; i < 2; ++i) {
        EXPECT_EQ(back->images[i].srgb, scene->images[i].srgb);
        EXPECT_EQ(back->images[i].pixels.pixels, scene->images[i].pixels.pixels);  // 8-bit values survive PNG exactly
    }
    const rg::Material &a = scene->materials[0], &b = back->materials[0];
    for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r) EXPECT_NEAR(a.baseColorTex.transform[c][r], b.baseColorTex.transform[c][r], 1e-6f);
    EXPECT_EQ(b.normalTex.texCoord, 1u);
    EXPECT_EQ(b.alphaMode, rg::AlphaMode::Mask);
    EXPECT_FLOAT_EQ(b.alphaCutoff, 0.4f);
    ASSERT_EQ(back->samplers.size(), 1u);
    EXPECT_EQ(back->samplers[0], scene->samplers[0]);
    EXPECT_EQ(b.baseColorTex.sampler, 0);
}

TEST(ExportGlb, FilesTheSceneNamesAreWrittenRelativeToTheGlb) {
    // An IES profile and an environment image: the .glb names them relative to its own folder
    // (no machine path), and reading it back finds the same files; an absolute path in those
    // extras is refused.
    const std::string dir = tmpDir("export_relative");
    fs::create_directories(dir + "/assets");
    fs::copy_file(std::string(RG_SOURCE_ROOT) + "/tests/unit/ies/downlight_2002.ies", dir + "/assets/d.ies", fs::copy_options::overwrite_existing);
    rg::Scene scene;
    rg::Light l;
    l.name = "lamp";
    l.type = rg::LightType::Point;
    l.unit = "lm";
    l.intensity = 800;
    l.ies = dir + "/assets/d.ies";
    scene.lights.push_back(l);
    rg::Environment e;
    e.kind = "hdr";
    e.file = dir + "/assets/sky.exr";
    scene.environment = e;
    fs::create_directories(dir + "/out");
    ASSERT_TRUE(rg::exportGlb(scene, dir + "/out/s.glb"));
    const auto raw = readBytes(dir + "/out/s.glb");
    const std::string bytes(raw.begin(), raw.end());
    EXPECT_NE(bytes.find("\"../assets/d.ies\""), std::string::npos);
    EXPECT_EQ(bytes.find(dir), std::string::npos);  // no machine path
    auto back = rg::loadGltf(dir + "/out/s.glb");
    ASSERT_TRUE(back) << errorOf(back);
    ASSERT_EQ(back->lights.size(), 1u);
    EXPECT_EQ(fs::path(back->lights[0].ies).lexically_normal(), fs::path(dir + "/assets/d.ies").lexically_normal());
    ASSERT_TRUE(back->environment.has_value());
    EXPECT_EQ(fs::path(back->environment->file).lexically_normal(), fs::path(dir + "/assets/sky.exr").lexically_normal());
    GltfBuilder g;
    g.j["scenes"] = json::array({{{"nodes", json::array()}, {"extras", {{"rgraph", {{"environment", {{"kind", "hdr"}, {"file", "/etc/passwd"}}}}}}}}});
    g.j["scene"] = 0;
    auto refused = rg::loadGltf(g.writeGltf(dir, "abs"));
    ASSERT_FALSE(refused);
    EXPECT_NE(refused.error().message.find("'/etc/passwd' is an absolute path"), std::string::npos) << refused.error().message;
}

TEST(ExportGlb, FailedWriteLeavesNothingBehind) {
    const std::string dir = tmpDir("export_fail");
    rg::Scene empty;
    auto r = rg::exportGlb(empty, dir + "/no/such/dir/x.glb");
    ASSERT_FALSE(r);
    EXPECT_EQ(r.error().code, ErrorCode::Io);
    EXPECT_EQ(r.error().message, "cannot write '" + dir + "/no/such/dir/x.glb': No such file or directory");
    ASSERT_TRUE(rg::exportGlb(empty, dir + "/e.glb"));
    auto back = rg::loadGltf(dir + "/e.glb");
    ASSERT_TRUE(back) << errorOf(back);
    EXPECT_TRUE(back->nodes.empty());
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);  // no temp file left
}

}  // namespace

TEST(SceneGeometry, SphereLevelsOfDetailDropRowsAndStayWithinTheirError) {
    // A 96-segment sphere carries 48- and 24-segment levels over the same vertices (12 segments
    // would be under the floor of 24). Each level's triangles are the full grid's every 2nd / 4th
    // ring and segment, so every corner is a vertex of the sphere; the stated error bounds how far
    // the sphere bulges above any triangle (the plane's distance from the centre).
    const float radius = 0.45f;
    const rg::Primitive p = rg::makeSphere(radius, 96, 0);
    ASSERT_EQ(p.lods.size(), 2u);
    EXPECT_EQ(rg::makeSphere(radius, 48, 0).lods.size(), 1u);  // 24 segments only
    EXPECT_EQ(p.indices.size(), size_t(3 * (96 * 48 * 2 - 2 * 96)));  // the poles' rows have one triangle a quad
    const uint32_t row = 97;
    float previous = 0.0f;
    for (size_t l = 0; l < p.lods.size(); ++l) {
        const uint32_t stride = 2u << l, segments = 96 / stride, rings = 48 / stride;
        const rg::PrimitiveLod& lod = p.lods[l];
        EXPECT_EQ(lod.indices.size(), size_t(3 * (segments * rings * 2 - 2 * segments))) << "level " << l + 1;
        EXPECT_GT(lod.error, previous);
        previous = lod.error;
        float bulge = 0.0f;
        for (size_t t = 0; t + 2 < lod.indices.size(); t += 3) {
            glm::vec3 c[3];
            for (size_t k = 0; k < 3; ++k) {
                const uint32_t v = lod.indices[t + k];
                ASSERT_EQ(v / row % stride, 0u) << "ring of vertex " << v;
                ASSERT_EQ(v % row % stride, 0u) << "segment of vertex " << v;
                c[k] = p.vertices[v].position;
            }
            const glm::vec3 n = glm::cross(c[1] - c[0], c[2] - c[0]);
            ASSERT_GT(glm::length(n), 0.0f) << "degenerate triangle at " << t;
            // Outward-facing (counter-clockwise seen from outside), as the full mesh's.
            EXPECT_GT(glm::dot(n, c[0] + c[1] + c[2]), 0.0f);
            bulge = std::max(bulge, radius - std::abs(glm::dot(glm::normalize(n), c[0])));
        }
        std::printf("level %zu: %u segments, %zu triangles, error %.2f mm, largest bulge %.2f mm\n", l + 1, segments,
                    lod.indices.size() / 3, lod.error * 1e3f, bulge * 1e3f);
        EXPECT_LE(bulge, lod.error);
        EXPECT_GT(bulge, 0.5f * lod.error);  // and the bound is not loose by more than 2x
    }
    // A sphere whose grid cannot drop every other ring has none (30 segments: 15 rings).
    EXPECT_TRUE(rg::makeSphere(1.0f, 30, 0).lods.empty());
}

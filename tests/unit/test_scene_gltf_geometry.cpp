// glTF geometry as exporters write it: EXT_meshopt_compression views (encoded here by Debian's
// meshoptimizer), morph targets at the mesh's and a node's weights, skinned meshes posed by their
// joints. Each test fails when the loader ignores what it checks.
#include <meshoptimizer.h>

#include <algorithm>
#include <array>

#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "scene_test_util.h"

namespace {

using namespace rg::test;

rg::GltfOptions noImages() {
    rg::GltfOptions o;
    o.loadImages = false;
    o.buildLods = false;
    return o;
}

// A grid of (n+1)² vertices over [0, 1]² in XY: positions, unit normals leaning with x, uvs.
struct Grid {
    std::vector<float> pos, nrm, uv;  // 3, 4 (w = 0, for the octahedral filter), 2 per vertex
    std::vector<uint32_t> idx;
    explicit Grid(int n) {
        for (int y = 0; y <= n; ++y)
            for (int x = 0; x <= n; ++x) {
                const float u = float(x) / float(n), v = float(y) / float(n);
                pos.insert(pos.end(), {u, v, 0.25f * u * v});
                const glm::vec3 d = glm::normalize(glm::vec3(u - 0.5f, 0.3f * v, 1.0f));
                nrm.insert(nrm.end(), {d.x, d.y, d.z, 0.0f});
                uv.insert(uv.end(), {3.0f * u, 1.0f - v});
            }
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                const uint32_t a = uint32_t(y * (n + 1) + x), b = a + 1, c = a + uint32_t(n) + 1;
                idx.insert(idx.end(), {a, b, c + 1, a, c + 1, c});
            }
    }
    size_t vertices() const { return pos.size() / 3; }
};

// One EXT_meshopt_compression view: `encoded` in buffer 0, decoding into buffer 1 (the fallback,
// no bytes in the file) at `fallbackOffset`.
int compressedView(GltfBuilder& g, const std::vector<unsigned char>& encoded, size_t count,
                   size_t stride, const char* mode, const char* filter, size_t& fallbackOffset) {
    while (g.bin.size() % 4) g.bin.push_back(0);
    const size_t at = g.bin.size();
    g.bin.insert(g.bin.end(), encoded.begin(), encoded.end());
    json ext = {{"buffer", 0},          {"byteOffset", at}, {"byteLength", encoded.size()},
                {"byteStride", stride}, {"count", count},   {"mode", mode}};
    if (std::string(filter) != "NONE") ext["filter"] = filter;
    json view = {{"buffer", 1},
                 {"byteOffset", fallbackOffset},
                 {"byteLength", count * stride},
                 {"extensions", {{"EXT_meshopt_compression", ext}}}};
    if (std::string(mode) == "ATTRIBUTES") view["byteStride"] = stride;
    g.j["bufferViews"].push_back(view);
    fallbackOffset += (count * stride + 3) / 4 * 4;
    return int(g.j["bufferViews"].size() - 1);
}

std::vector<unsigned char> encodeVertices(const void* data, size_t count, size_t stride) {
    std::vector<unsigned char> out(meshopt_encodeVertexBufferBound(count, stride));
    out.resize(meshopt_encodeVertexBuffer(out.data(), out.size(), data, count, stride));
    return out;
}

}  // namespace

// EXT_meshopt_compression: positions (no filter), normals (octahedral, 8 bits), uvs (exponential)
// and a triangle list, decoded into a fallback buffer the file leaves empty, load as the same grid
// within each encoding's quantisation, in .gltf and .glb; a broken view is refused by name.
TEST(GltfGeometry, MeshoptCompressedViewsDecodeToTheMeshTheyEncode) {
    const std::string dir = tmpDir("meshopt");
    const Grid grid(8);
    const size_t n = grid.vertices();
    std::vector<int8_t> oct(n * 4);
    meshopt_encodeFilterOct(oct.data(), n, 4, 8, grid.nrm.data());
    std::vector<uint32_t> exp(n * 2);
    meshopt_encodeFilterExp(exp.data(), n, 8, 15, grid.uv.data());
    std::vector<unsigned char> tri(meshopt_encodeIndexBufferBound(grid.idx.size(), n));
    tri.resize(meshopt_encodeIndexBuffer(tri.data(), tri.size(), grid.idx.data(), grid.idx.size()));

    auto build = [&](const std::vector<unsigned char>& positions, const char* mode) {
        GltfBuilder g;
        size_t fallback = 0;
        const int pv = compressedView(g, positions, n, 12, mode, "NONE", fallback);
        const int nv = compressedView(g, encodeVertices(oct.data(), n, 4), n, 4, "ATTRIBUTES",
                                      "OCTAHEDRAL", fallback);
        const int uv = compressedView(g, encodeVertices(exp.data(), n, 8), n, 8, "ATTRIBUTES",
                                      "EXPONENTIAL", fallback);
        const int iv = compressedView(g, tri, grid.idx.size(), 4, "TRIANGLES", "NONE", fallback);
        json attrs = {{"POSITION", g.accessor(pv, kFloat, n, "VEC3")},
                      {"NORMAL", g.accessor(nv, 5120, n, "VEC3", true)},
                      {"TEXCOORD_0", g.accessor(uv, kFloat, n, "VEC2")}};
        const int idx = g.accessor(iv, kUInt, grid.idx.size(), "SCALAR");
        g.mesh("grid", json::array({{{"attributes", attrs}, {"indices", idx}}}));
        g.scene({g.node({{"mesh", 0}})});
        g.moreBuffers.push_back(
            {{"byteLength", fallback},
             {"extensions", {{"EXT_meshopt_compression", {{"fallback", true}}}}}});
        g.j["extensionsUsed"] = {"EXT_meshopt_compression"};
        g.j["extensionsRequired"] = {"EXT_meshopt_compression"};
        return g;
    };
    const std::vector<unsigned char> positions = encodeVertices(grid.pos.data(), n, 12);
    GltfBuilder g = build(positions, "ATTRIBUTES");
    for (const std::string& path : {g.writeGltf(dir, "grid"), g.writeGlb(dir, "grid")}) {
        auto scene = rg::loadGltf(path, noImages());
        ASSERT_TRUE(scene) << path << ": " << errorOf(scene);
        EXPECT_TRUE(scene->warnings.empty()) << scene->warnings.front();
        const rg::Primitive& p = scene->meshes[0].primitives[0];
        ASSERT_EQ(p.vertices.size(), n) << path;
        // The index codec may start a triangle at another corner, never change its winding.
        ASSERT_EQ(p.indices.size(), grid.idx.size()) << path;
        for (size_t t = 0; t < grid.idx.size(); t += 3) {
            auto lowestFirst = [](const uint32_t* c) {
                std::array<uint32_t, 3> r = {c[0], c[1], c[2]};
                while (r[0] > r[1] || r[0] > r[2]) std::rotate(r.begin(), r.begin() + 1, r.end());
                return r;
            };
            EXPECT_EQ(lowestFirst(&p.indices[t]), lowestFirst(&grid.idx[t])) << path << " " << t;
        }
        float worstNormal = 0.0f, worstUv = 0.0f;
        for (size_t i = 0; i < n; ++i) {
            // The vertex codec is lossless; the filters quantise.
            EXPECT_EQ(p.vertices[i].position, glm::make_vec3(&grid.pos[3 * i])) << path << " " << i;
            worstNormal = std::max(
                worstNormal, glm::length(p.vertices[i].normal - glm::make_vec3(&grid.nrm[4 * i])));
            worstUv =
                std::max(worstUv, glm::length(p.vertices[i].uv0 - glm::make_vec2(&grid.uv[2 * i])));
        }
        EXPECT_LT(worstNormal, 0.02f) << path;        // 8-bit octahedral: ~1/127 per axis
        EXPECT_GT(worstNormal, 0.0f) << path;         // quantised: they came through the filter
        EXPECT_LT(worstUv, 3.0f / 16384.0f) << path;  // 15-bit shared mantissa
    }

    // Broken views, each named.
    std::vector<unsigned char> garbage = positions;
    for (size_t i = 1; i < garbage.size(); i += 3) garbage[i] ^= 0x5a;
    garbage.resize(garbage.size() / 2);
    auto broken = rg::loadGltf(build(garbage, "ATTRIBUTES").writeGltf(dir, "garbage"), noImages());
    ASSERT_FALSE(broken);
    EXPECT_NE(broken.error().message.find(
                  "buffer view 0: EXT_meshopt_compression: the ATTRIBUTES data does not decode"),
              std::string::npos)
        << broken.error().message;
    auto mode = rg::loadGltf(build(positions, "VERTICES").writeGltf(dir, "mode"), noImages());
    ASSERT_FALSE(mode);
    EXPECT_NE(mode.error().message.find("EXT_meshopt_compression.mode: 'VERTICES', expected "
                                        "ATTRIBUTES, TRIANGLES or INDICES"),
              std::string::npos)
        << mode.error().message;
    // A count the compressed bytes cannot hold is refused before anything is allocated.
    GltfBuilder big = build(positions, "ATTRIBUTES");
    big.j["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["count"] = 1u << 28;
    big.j["bufferViews"][0]["byteLength"] = uint64_t(12) << 28;
    auto huge = rg::loadGltf(big.writeGltf(dir, "huge"), noImages());
    ASSERT_FALSE(huge);
    EXPECT_NE(huge.error().message.find("elements of 12 bytes cannot come from"), std::string::npos)
        << huge.error().message;
    // So is a view placed far into a fallback buffer that claims terabytes.
    GltfBuilder far = build(positions, "ATTRIBUTES");
    far.j["bufferViews"][0]["byteOffset"] = uint64_t(1) << 40;
    far.moreBuffers[0]["byteLength"] = uint64_t(1) << 41;
    auto farAway = rg::loadGltf(far.writeGltf(dir, "far"), noImages());
    ASSERT_FALSE(farAway);
    EXPECT_NE(farAway.error().message.find("of its fallback buffer (at most 2147483648)"),
              std::string::npos)
        << farAway.error().message;
}

// Morph targets (glTF §3.7.2.2): a quad lifted by its target's POSITION displacement times the
// mesh's default weight, its normal tilted by the NORMAL target; a node with weights of its own
// draws its own copy; weights that do not match the targets are refused.
TEST(GltfGeometry, MorphTargetsApplyTheMeshsAndTheNodesWeights) {
    const std::string dir = tmpDir("morph");
    auto build = [&](const json& meshWeights, const json& nodeWeights) {
        GltfBuilder g;
        addQuad(g, /*withNormals=*/true);
        const std::vector<float> up = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
        const std::vector<float> tilt = {1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0};
        const std::vector<float> side = {0, 2, 0, 0, 2, 0, 0, 2, 0, 0, 2, 0};
        g.j["meshes"][0]["primitives"][0]["targets"] = {
            {{"POSITION", g.floats(up, "VEC3")}, {"NORMAL", g.floats(tilt, "VEC3")}},
            {{"POSITION", g.floats(side, "VEC3")}}};
        if (!meshWeights.is_null()) g.j["meshes"][0]["weights"] = meshWeights;
        json second = {{"mesh", 0}, {"translation", {5, 0, 0}}};
        if (!nodeWeights.is_null()) second["weights"] = nodeWeights;
        g.scene({g.node({{"mesh", 0}}), g.node(second)});
        return g;
    };
    auto scene = rg::loadGltf(build({0.5, 0.25}, {1.0, 0.0}).writeGltf(dir, "morph"), noImages());
    ASSERT_TRUE(scene) << errorOf(scene);
    ASSERT_EQ(scene->nodes.size(), 2u);
    const rg::Mesh& meshDefault = scene->meshes[size_t(scene->nodes[0].mesh)];
    const rg::Mesh& meshNode = scene->meshes[size_t(scene->nodes[1].mesh)];
    ASSERT_NE(scene->nodes[0].mesh, scene->nodes[1].mesh);
    // Vertex 2 of the quad is (1, 1, 0): + 0.5·(0, 0, 1) + 0.25·(0, 2, 0).
    expectNear(meshDefault.primitives[0].vertices[2].position, {1.0f, 1.5f, 0.5f}, 1e-6f,
               "mesh weights");
    expectNear(meshDefault.primitives[0].vertices[2].normal,
               glm::normalize(glm::vec3(0.5f, 0.0f, 1.0f)), 1e-6f, "mesh weights' normal");
    expectNear(meshNode.primitives[0].vertices[2].position, {1.0f, 1.0f, 1.0f}, 1e-6f,
               "node weights");
    expectNear(meshNode.primitives[0].vertices[2].normal,
               glm::normalize(glm::vec3(1.0f, 0.0f, 1.0f)), 1e-6f, "node weights' normal");

    // Without weights, the targets are at rest (weight 0).
    auto rest = rg::loadGltf(build(nullptr, nullptr).writeGltf(dir, "rest"), noImages());
    ASSERT_TRUE(rest) << errorOf(rest);
    expectNear(rest->meshes[0].primitives[0].vertices[2].position, {1.0f, 1.0f, 0.0f}, 0.0f,
               "rest");
    EXPECT_EQ(rest->nodes[0].mesh, rest->nodes[1].mesh);

    auto wrong = rg::loadGltf(build({0.5}, nullptr).writeGltf(dir, "wrong"), noImages());
    ASSERT_FALSE(wrong);
    EXPECT_NE(
        wrong.error().message.find("mesh 0 'quad': weights has 1 values, the mesh 2 morph targets"),
        std::string::npos)
        << wrong.error().message;
    // A node naming a mesh beyond the file's is refused, even once a morphed copy exists.
    GltfBuilder beyond = build(nullptr, {1.0, 0.0});
    beyond.j["nodes"].push_back({{"mesh", 1}});
    beyond.j["scenes"][0]["nodes"].push_back(2);
    auto noMesh = rg::loadGltf(beyond.writeGltf(dir, "beyond"), noImages());
    ASSERT_FALSE(noMesh);
    EXPECT_NE(noMesh.error().message.find("node 2: mesh 1 does not exist (1 meshes)"),
              std::string::npos)
        << noMesh.error().message;
    auto wrongNode =
        rg::loadGltf(build(nullptr, {1, 2, 3}).writeGltf(dir, "wrongnode"), noImages());
    ASSERT_FALSE(wrongNode);
    EXPECT_NE(wrongNode.error().message.find("node 1: weights has 3 values"), std::string::npos)
        << wrongNode.error().message;
}

// Skins (glTF §3.7.3): a two-bone strip whose upper row follows joint 1, turned 90° about z at
// (0, 1, 0), lands where world(joint) · inverseBind puts it; the middle row, half on each joint,
// halfway; the skinned node's own translation does not apply; a joint beyond the skin's is
// refused by name.
TEST(GltfGeometry, SkinnedMeshesArePosedByTheirJoints) {
    const std::string dir = tmpDir("skin");
    auto build = [&](uint8_t lastJoint, bool withNormals = true) {
        GltfBuilder g;
        // Three rows of two vertices: y = 0 (joint 0), y = 1 (half and half), y = 2 (joint 1).
        const std::vector<float> pos = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 0, 2, 0, 1, 2, 0};
        std::vector<float> tan;
        for (int i = 0; i < 6; ++i) tan.insert(tan.end(), {1, 0, 0, 1});
        const std::vector<uint8_t> joints = {0, 0, 0, 0, 0, 0, 0, 0, 0,         1, 0, 0,
                                             0, 1, 0, 0, 1, 0, 0, 0, lastJoint, 0, 0, 0};
        const std::vector<float> weights = {1,    0,    0, 0, 1, 0, 0, 0, 0.5f, 0.5f, 0, 0,
                                            0.5f, 0.5f, 0, 0, 1, 0, 0, 0, 1,    0,    0, 0};
        const std::vector<float> nrm = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
        json attrs = {
            {"POSITION", g.floats(pos, "VEC3")},
            {"TANGENT", g.floats(tan, "VEC4")},
            {"JOINTS_0", g.accessor(g.view(joints.data(), joints.size()), kUByte, 6, "VEC4")},
            {"WEIGHTS_0", g.floats(weights, "VEC4")}};
        if (withNormals) attrs["NORMAL"] = g.floats(nrm, "VEC3");
        const int idx = g.indices16({0, 1, 3, 0, 3, 2, 2, 3, 5, 2, 5, 4});
        // The same vertices as a LINE_STRIP too: lines are posed like triangles.
        g.mesh("strip", json::array({{{"attributes", attrs}, {"indices", idx}},
                                     {{"attributes", attrs}, {"mode", 3}}}));
        // Joint 1's bind pose is at (0, 1, 0): its inverse moves down by 1.
        const glm::mat4 inverseBind1 = glm::translate(glm::mat4(1.0f), glm::vec3(0, -1, 0));
        std::vector<float> ibm(32);
        const glm::mat4 identity(1.0f);
        std::memcpy(ibm.data(), &identity[0][0], 64);
        std::memcpy(ibm.data() + 16, &inverseBind1[0][0], 64);
        const int ibmAccessor = g.accessor(g.view(ibm.data(), ibm.size() * 4), kFloat, 2, "MAT4");
        const glm::quat turn = glm::angleAxis(glm::radians(90.0f), glm::vec3(0, 0, 1));
        const int bone1 = g.node({{"name", "bone1"},
                                  {"translation", {0, 1, 0}},
                                  {"rotation", {turn.x, turn.y, turn.z, turn.w}}});
        const int bone0 = g.node({{"name", "bone0"}, {"children", {bone1}}});
        const int body =
            g.node({{"name", "body"}, {"mesh", 0}, {"skin", 0}, {"translation", {100, 0, 0}}});
        g.j["skins"] = {{{"joints", {bone0, bone1}}, {"inverseBindMatrices", ibmAccessor}}};
        g.scene({body, bone0});
        return g;
    };
    auto scene = rg::loadGltf(build(1).writeGltf(dir, "skin"), noImages());
    ASSERT_TRUE(scene) << errorOf(scene);
    ASSERT_EQ(scene->nodes.size(), 1u);
    EXPECT_EQ(scene->nodes[0].world, glm::mat4(1.0f));
    const auto& v = scene->meshes[size_t(scene->nodes[0].mesh)].primitives[0].vertices;
    // Joint 1: translate(0, 1, 0) · rotZ(90°) · translate(0, -1, 0) takes (x, y) to (1 - y, x + 1).
    expectNear(v[0].position, {0, 0, 0}, 1e-6f, "joint 0");
    expectNear(v[1].position, {1, 0, 0}, 1e-6f, "joint 0");
    expectNear(v[4].position, {-1, 1, 0}, 1e-6f, "joint 1");
    expectNear(v[5].position, {-1, 2, 0}, 1e-6f, "joint 1");
    // Half and half at y = 1: joint 0 leaves (1, 1); joint 1 turns it to (0, 2): the mean.
    expectNear(v[3].position, {0.5f, 1.5f, 0}, 1e-6f, "blended");
    expectNear(glm::vec3(v[5].tangent), {0, 1, 0}, 1e-6f, "joint 1's tangent");
    expectNear(glm::vec3(v[0].tangent), {1, 0, 0}, 1e-6f, "joint 0's tangent");
    for (const rg::Vertex& x : v) expectNear(x.normal, {0, 0, 1}, 1e-6f, "normal");
    const auto& line = scene->meshes[size_t(scene->nodes[0].mesh)].lines;
    ASSERT_EQ(line.size(), 1u);
    EXPECT_EQ(line[0].indices, (std::vector<uint32_t>{0, 1, 1, 2, 2, 3, 3, 4, 4, 5}));
    expectNear(line[0].vertices[3].position, {0.5f, 1.5f, 0}, 1e-6f, "line, blended");
    expectNear(line[0].vertices[5].position, {-1, 2, 0}, 1e-6f, "line, joint 1");
    // The source mesh is unchanged (another node could draw it unskinned).
    expectNear(scene->meshes[0].primitives[0].vertices[5].position, {1, 2, 0}, 0.0f, "source");

    // Without normals each triangle gets its own corners (flat normals); their joints follow,
    // and the normals are made anew from the posed triangles.
    auto flat = rg::loadGltf(build(1, false).writeGltf(dir, "flat"), noImages());
    ASSERT_TRUE(flat) << errorOf(flat);
    const auto& f = flat->meshes[size_t(flat->nodes[0].mesh)].primitives[0].vertices;
    ASSERT_EQ(f.size(), 12u);
    for (const rg::Vertex& x : f) expectNear(x.normal, {0, 0, 1}, 1e-6f, "flat normal");
    expectNear(f[11].position, {-1, 1, 0}, 1e-6f, "flat: last triangle's corner 4");

    auto beyond = rg::loadGltf(build(7).writeGltf(dir, "beyond"), noImages());
    ASSERT_FALSE(beyond);
    EXPECT_NE(beyond.error().message.find(
                  "node 2 'body': primitive 0 vertex 5 names joint 7, skin 0 has 2"),
              std::string::npos)
        << beyond.error().message;
}

// Any TEXCOORD_n a texture names: a material's sets beyond 0 and 1 take a uv slot its textures
// leave free (TEXCOORD_1, the lightmap's, keeps slot 1 where it can), every primitive drawn with
// it reads that set there; a third set is named in a warning.
TEST(GltfGeometry, TexturesReadTheTexcoordSetTheyName) {
    const std::string dir = tmpDir("texcoord");
    writeTestPng(dir + "/t.png", 1, 1, {1, 1, 1, 1});
    GltfBuilder g;
    const std::vector<float> pos = {0, 0, 0, 1, 0, 0, 1, 1, 0};
    json attrs = {{"POSITION", g.floats(pos, "VEC3")}};
    for (int set = 0; set < 4; ++set) {
        const float u = 0.1f * float(set + 1);  // TEXCOORD_n holds (u, -u) everywhere
        attrs["TEXCOORD_" + std::to_string(set)] = g.floats({u, -u, u, -u, u, -u}, "VEC2");
    }
    g.j["images"] = json::array({{{"uri", "t.png"}}});
    g.j["textures"] = json::array({{{"source", 0}}});
    auto tex = [](int set) { return json{{"index", 0}, {"texCoord", set}}; };
    g.j["materials"] =
        json::array({{{"name", "two"}, {"pbrMetallicRoughness", {{"baseColorTexture", tex(2)}}}},
                     {{"name", "zero_three"},
                      {"pbrMetallicRoughness", {{"baseColorTexture", tex(0)}}},
                      {"normalTexture", tex(3)}},
                     {{"name", "three_sets"},
                      {"pbrMetallicRoughness", {{"baseColorTexture", tex(0)}}},
                      {"normalTexture", tex(1)},
                      {"occlusionTexture", tex(2)}}});
    json prims = json::array();
    for (int m = 0; m < 3; ++m) prims.push_back({{"attributes", attrs}, {"material", m}});
    g.mesh("tri", prims);
    g.scene({g.node({{"mesh", 0}})});
    auto scene = rg::loadGltf(g.writeGltf(dir, "texcoord"), noImages());
    ASSERT_TRUE(scene) << errorOf(scene);
    const auto& p = scene->meshes[0].primitives;
    const auto& mats = scene->materials;
    // "two": TEXCOORD_2 in slot 0, TEXCOORD_1 stays in slot 1 (and is still the lightmap's).
    EXPECT_EQ(mats[0].baseColorTex.texCoord, 0u);
    EXPECT_FLOAT_EQ(p[0].vertices[0].uv0.x, 0.3f);
    EXPECT_FLOAT_EQ(p[0].vertices[0].uv1.x, 0.2f);
    EXPECT_TRUE(p[0].lightmapUv);
    // "zero_three": TEXCOORD_0 in slot 0, TEXCOORD_3 in slot 1 (no lightmap uvs there).
    EXPECT_EQ(mats[1].baseColorTex.texCoord, 0u);
    EXPECT_EQ(mats[1].normalTex.texCoord, 1u);
    EXPECT_FLOAT_EQ(p[1].vertices[2].uv0.x, 0.1f);
    EXPECT_FLOAT_EQ(p[1].vertices[2].uv1.y, -0.4f);
    EXPECT_FALSE(p[1].lightmapUv);
    // "three_sets": no slot for TEXCOORD_2; named, and read from slot 0.
    EXPECT_EQ(mats[2].occlusionTex.texCoord, 0u);
    EXPECT_EQ(mats[2].normalTex.texCoord, 1u);
    bool named = false;
    for (const auto& w : scene->warnings)
        named |= w.find("material 2 'three_sets'") != std::string::npos &&
                 w.find(
                     "more than two texture coordinate sets; those on TEXCOORD_2 read "
                     "TEXCOORD_0") != std::string::npos;
    EXPECT_TRUE(named) << (scene->warnings.empty() ? "no warnings" : scene->warnings.back());
}

// COLOR_0: float RGB (alpha 1) and normalised unsigned short RGBA load as the vertex's linear
// colour (16-bit unorm), white without; exportGlb writes it back and the file loads the same.
TEST(GltfGeometry, VertexColorsLoadAndRoundTrip) {
    const std::string dir = tmpDir("color");
    GltfBuilder g;
    const std::vector<float> pos = {0, 0, 0, 1, 0, 0, 1, 1, 0};
    const int p = g.floats(pos, "VEC3");
    const int rgb = g.floats({1, 0, 0, 0, 0.5f, 0, 0.25f, 0.25f, 2.0f}, "VEC3");
    const std::vector<uint16_t> rgba = {0, 65535, 0, 32768, 65535, 65535, 65535, 0, 1, 2, 3, 4};
    const int shorts = g.accessor(g.view(rgba.data(), rgba.size() * 2), kUShort, 3, "VEC4", true);
    g.mesh("tri", json::array({{{"attributes", {{"POSITION", p}, {"COLOR_0", rgb}}}},
                               {{"attributes", {{"POSITION", p}, {"COLOR_0", shorts}}}},
                               {{"attributes", {{"POSITION", p}}}}}));
    g.scene({g.node({{"mesh", 0}})});
    auto scene = rg::loadGltf(g.writeGltf(dir, "color"), noImages());
    ASSERT_TRUE(scene) << errorOf(scene);
    auto check = [](const rg::Scene& s, const char* what) {
        const auto& prims = s.meshes[0].primitives;
        // Flat normals gave each triangle its own corners, in index order.
        EXPECT_EQ(prims[0].vertices[0].color, glm::u16vec4(65535, 0, 0, 65535)) << what;
        EXPECT_EQ(prims[0].vertices[1].color, glm::u16vec4(0, 32768, 0, 65535)) << what;
        EXPECT_EQ(prims[0].vertices[2].color, glm::u16vec4(16384, 16384, 65535, 65535))
            << what << ": 0.25 and a value above 1 clamped";
        EXPECT_EQ(prims[1].vertices[1].color, glm::u16vec4(65535, 65535, 65535, 0)) << what;
        EXPECT_EQ(prims[1].vertices[2].color, glm::u16vec4(1, 2, 3, 4)) << what;
        EXPECT_EQ(prims[2].vertices[0].color, glm::u16vec4(65535)) << what << ": none is white";
    };
    check(*scene, "loaded");
    ASSERT_TRUE(rg::exportGlb(*scene, dir + "/color.glb"));
    auto back = rg::loadGltf(dir + "/color.glb", noImages());
    ASSERT_TRUE(back) << errorOf(back);
    check(*back, "exported and loaded again");
}

// Points and lines (glTF 3.7.2.1): LINES as they are, LINE_STRIP and LINE_LOOP as segment lists
// (a loop closed back to its first vertex), POINTS as they are — each in the mesh's own list,
// with its material and COLOR_0; a mesh of lines alone still bounds the scene.
TEST(GltfGeometry, PointsAndLinesLoadAsSegmentAndPointLists) {
    const std::string dir = tmpDir("lines");
    GltfBuilder g;
    const int p = g.floats({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0}, "VEC3");
    const int rgb = g.floats({1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1}, "VEC3");
    const int idx = g.indices16({3, 2, 1, 0});
    g.j["materials"] = {{{"name", "ink"}}};
    auto prim = [&](int mode, bool indexed) {
        json j = {
            {"attributes", {{"POSITION", p}, {"COLOR_0", rgb}}}, {"mode", mode}, {"material", 0}};
        if (indexed) j["indices"] = idx;
        return j;
    };
    g.mesh("strokes", json::array({prim(1, true), prim(3, false), prim(2, true), prim(0, false),
                                   prim(2, false)}));
    g.scene({g.node({{"mesh", 0}, {"translation", {0, 0, -5}}})});
    auto scene = rg::loadGltf(g.writeGltf(dir, "lines"), noImages());
    ASSERT_TRUE(scene) << errorOf(scene);
    EXPECT_TRUE(scene->warnings.empty()) << scene->warnings.front();
    const rg::Mesh& m = scene->meshes[0];
    EXPECT_TRUE(m.primitives.empty());
    ASSERT_EQ(m.lines.size(), 4u);
    EXPECT_EQ(m.lines[0].indices, (std::vector<uint32_t>{3, 2, 1, 0}));              // LINES
    EXPECT_EQ(m.lines[1].indices, (std::vector<uint32_t>{0, 1, 1, 2, 2, 3}));        // strip
    EXPECT_EQ(m.lines[2].indices, (std::vector<uint32_t>{3, 2, 2, 1, 1, 0, 0, 3}));  // loop
    EXPECT_EQ(m.lines[3].indices, (std::vector<uint32_t>{0, 1, 1, 2, 2, 3, 3, 0}));  // loop
    ASSERT_EQ(m.points.size(), 1u);
    EXPECT_EQ(m.points[0].indices, (std::vector<uint32_t>{0, 1, 2, 3}));
    EXPECT_EQ(m.points[0].vertices.size(), 4u);
    EXPECT_EQ(m.lines[1].vertices[1].color, glm::u16vec4(0, 65535, 0, 65535));
    EXPECT_EQ(scene->materials[m.lines[0].material].name, "ink");
    expectNear(scene->boundsMin, {0, 0, -5}, 0.0f, "bounds");
    expectNear(scene->boundsMax, {1, 1, -5}, 0.0f, "bounds");
    // exportGlb writes them back as LINES and POINTS.
    ASSERT_TRUE(rg::exportGlb(*scene, dir + "/lines.glb"));
    auto back = rg::loadGltf(dir + "/lines.glb", noImages());
    ASSERT_TRUE(back) << errorOf(back);
    ASSERT_EQ(back->meshes[0].lines.size(), 4u);
    ASSERT_EQ(back->meshes[0].points.size(), 1u);
    for (size_t k = 0; k < 4; ++k) EXPECT_EQ(back->meshes[0].lines[k].indices, m.lines[k].indices);
    EXPECT_EQ(back->meshes[0].points[0].indices, m.points[0].indices);
    EXPECT_EQ(back->meshes[0].lines[1].vertices[1].color, glm::u16vec4(0, 65535, 0, 65535));
}

// MikkTSpace (glTF 2.0 §3.7.2.1): each corner's dP/du weighted by the corner's angle, and a vertex
// between mirrored uv halves split in two. The expected frames follow from the algorithm's
// definition on meshes simple enough to do by hand.
TEST(GltfGeometry, GeneratedTangentsFollowMikkTSpace) {
    // Two quads side by side, the right one's u mirrored: the seam vertices (x = 1) serve both.
    // Left: u = x (dP/du = +x, uv area negative: w = +1); right: u = 2 − x (−x, w = −1).
    rg::Primitive strip;
    for (int y = 0; y <= 1; ++y)
        for (int x = 0; x <= 2; ++x) {
            rg::Vertex v;
            v.position = glm::vec3(x, y, 0);
            v.normal = glm::vec3(0, 0, 1);
            v.uv0 = glm::vec2(x <= 1 ? float(x) : float(2 - x), 1.0f - float(y));
            strip.vertices.push_back(v);
        }
    strip.indices = {0, 1, 4, 0, 4, 3, 1, 2, 5, 1, 5, 4};
    const std::vector<uint32_t> copied = rg::generateTangents(strip);
    EXPECT_EQ(copied, (std::vector<uint32_t>{1, 4}));  // the seam's two vertices
    ASSERT_EQ(strip.vertices.size(), 8u);
    for (size_t c = 0; c < strip.indices.size(); ++c) {
        const glm::vec4 t = strip.vertices[strip.indices[c]].tangent;
        const bool right = c >= 6;
        expectNear(glm::vec3(t), {right ? -1.0f : 1.0f, 0, 0}, 1e-6f,
                   "corner " + std::to_string(c));
        EXPECT_EQ(t.w, right ? -1.0f : 1.0f) << "corner " << c;
        EXPECT_EQ(strip.vertices[strip.indices[c]].position,
                  glm::vec3(float(c < 6 ? std::array{0, 1, 1, 0, 1, 0}[c % 6]
                                        : std::array{1, 2, 2, 1, 2, 1}[c % 6]),
                            float(std::array{0, 0, 1, 0, 1, 1}[c % 6]), 0.0f))
            << "the split keeps every corner where it was";
    }

    // One vertex shared by a 90° corner whose uvs give dP/du = +x and a 30° corner whose uvs give
    // +y: MikkTSpace weights them by angle, (π/2)·x + (π/6)·y, at atan(1/3) = 18.4° from x — not
    // by uv area (45° here, both gradients being unit).
    rg::Primitive fan;
    auto vertex = [&](glm::vec3 p, glm::vec2 uv) {
        rg::Vertex v;
        v.position = p;
        v.normal = glm::vec3(0, 0, 1);
        v.uv0 = uv;
        fan.vertices.push_back(v);
        return static_cast<uint32_t>(fan.vertices.size() - 1);
    };
    const float c120 = std::cos(glm::radians(120.0f)), s120 = std::sin(glm::radians(120.0f));
    const float c150 = std::cos(glm::radians(150.0f)), s150 = std::sin(glm::radians(150.0f));
    const uint32_t o = vertex({0, 0, 0}, {0, 0});
    // First corner: u = x, v = −y. Second: u = y, v = x.
    const uint32_t a = vertex({1, 0, 0}, {1, 0}), b = vertex({0, 1, 0}, {0, -1});
    const uint32_t c = vertex({2 * c120, 2 * s120, 0}, {2 * s120, 2 * c120}),
                   d = vertex({2 * c150, 2 * s150, 0}, {2 * s150, 2 * c150});
    fan.indices = {o, a, b, o, c, d};
    EXPECT_TRUE(rg::generateTangents(fan).empty());
    const glm::vec3 want = glm::normalize(glm::vec3(glm::pi<float>() / 2, glm::pi<float>() / 6, 0));
    expectNear(glm::vec3(fan.vertices[o].tangent), want, 1e-5f, "angle-weighted");
    EXPECT_EQ(fan.vertices[o].tangent.w, 1.0f);

    // The loader takes the normal map's uv set: TEXCOORD_1 runs along +y where TEXCOORD_0 runs
    // along +x, and the normal map names set 1.
    const std::string dir = tmpDir("mikk");
    GltfBuilder g;
    const int p = g.floats({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0}, "VEC3");
    const int n = g.floats({0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3");
    const int uv0 = g.floats({0, 1, 1, 1, 1, 0, 0, 0}, "VEC2");
    const int uv1 = g.floats({0, 0, 0, 1, 1, 1, 1, 0}, "VEC2");  // (u, v) = (y, x)
    g.mesh(
        "quad",
        json::array({{{"attributes",
                       {{"POSITION", p}, {"NORMAL", n}, {"TEXCOORD_0", uv0}, {"TEXCOORD_1", uv1}}},
                      {"indices", g.indices16({0, 1, 2, 0, 2, 3})},
                      {"material", 0}}}));
    g.j["images"] = json::array({{{"uri", "n.png"}}});
    g.j["textures"] = json::array({{{"source", 0}}});
    g.j["materials"] = json::array({{{"normalTexture", {{"index", 0}, {"texCoord", 1}}}}});
    g.scene({g.node({{"mesh", 0}})});
    auto scene = rg::loadGltf(g.writeGltf(dir, "m"), noImages());
    ASSERT_TRUE(scene) << errorOf(scene);
    for (const rg::Vertex& v : scene->meshes[0].primitives[0].vertices)
        expectNear(glm::vec3(v.tangent), {0, 1, 0}, 1e-6f, "tangent along TEXCOORD_1's u");
}

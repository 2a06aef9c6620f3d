// glTF files that cannot load: every kind of broken file (JSON, GLB, buffers, images, accessors,
// indices, modes, ranges, the node hierarchy), each with its exact error text. No GPU.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include <draco/compression/encode.h>
#include <draco/mesh/triangle_soup_mesh_builder.h>

#include "scene_test_util.h"

namespace {

using rg::ErrorCode;
using namespace rg::test;

// ---------------------------------------------------------------------------------------------
// glTF: every kind of broken file, with its exact message

TEST(GltfErrors, RequiredUnsupportedExtensionIsRefusedByName) {
    const std::string dir = tmpDir("ext");
    GltfBuilder g;
    addQuad(g, true);
    g.j["extensionsUsed"] = {"KHR_texture_basisu", "KHR_texture_transform"};
    g.j["extensionsRequired"] = {"KHR_texture_transform", "KHR_texture_basisu"};
    const std::string path = g.writeGlb(dir, "x");
    auto r = rg::loadGltf(path);
    ASSERT_FALSE(r);
    EXPECT_EQ(r.error().code, ErrorCode::Unsupported);
    EXPECT_EQ(
        r.error().message,
        "'" + path + "' requires extension 'KHR_texture_basisu', which rgraph does not support");
    // Used but not required: loads, with a warning.
    g.j.erase("extensionsRequired");
    auto loaded = rg::loadGltf(g.writeGlb(dir, "y"));
    ASSERT_TRUE(loaded);
    const std::vector<std::string>& warnings = loaded->warnings;
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_EQ(warnings[0],
              "'" + dir + "/y.glb': uses extension 'KHR_texture_basisu', which rgraph ignores");
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
                              "/b.gltf': invalid JSON at line 3, column 14: syntax error while "
                              "parsing value - unexpected '}'; "
                              "expected '[', '{', or a literal");
    // Garbage bytes and valid JSON that is not a glTF.
    writeBytes(dir + "/g.gltf", {0x00, 0xff, 0x13, 0x37});
    EXPECT_EQ(errorOf(rg::loadGltf(dir + "/g.gltf"))
                  .rfind("'" + dir + "/g.gltf': invalid JSON at line 1, column 1:", 0),
              0u)
        << errorOf(rg::loadGltf(dir + "/g.gltf"));
    writeText(dir + "/a.gltf", "[1, 2]");
    EXPECT_EQ(errorOf(rg::loadGltf(dir + "/a.gltf")),
              "'" + dir + "/a.gltf': invalid glTF: the top level is not a JSON object");
    writeText(dir + "/v.gltf", "{}");
    EXPECT_EQ(errorOf(rg::loadGltf(dir + "/v.gltf")),
              "'" + dir + "/v.gltf': invalid glTF: no asset.version (is this a glTF file?)");
    writeText(dir + "/old.gltf", R"({"asset": {"version": "1.0"}})");
    auto old = rg::loadGltf(dir + "/old.gltf");
    ASSERT_FALSE(old);
    EXPECT_EQ(old.error().code, ErrorCode::Unsupported);
    EXPECT_EQ(old.error().message,
              "'" + dir + "/old.gltf': glTF version 1.0 is not supported (only 2.x)");
    // What tinygltf itself refuses comes through with its reason.
    writeText(dir + "/t.gltf",
              R"({"asset": {"version": "2.0"}, "accessors": [{"count": 1, "type": "VEC3"}]})");
    EXPECT_EQ(
        errorOf(rg::loadGltf(dir + "/t.gltf")).rfind("'" + dir + "/t.gltf': invalid glTF: ", 0),
        0u);
}

TEST(GltfErrors, TruncatedGlb) {
    const std::string dir = tmpDir("trunc");
    GltfBuilder g;
    addQuad(g, true);
    g.scene({g.node({{"mesh", 0}})});
    auto bytes = readBytes(g.writeGlb(dir, "t"));
    bytes.resize(bytes.size() - 40);
    writeBytes(dir + "/t.glb", bytes);
    EXPECT_EQ(errorOf(rg::loadGltf(dir + "/t.glb")),
              "'" + dir + "/t.glb': truncated GLB: the header says " +
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
    EXPECT_EQ(errorOf(r), "'" + path + "': buffer 0 'scene.bin': cannot open '" + dir +
                              "/scene.bin': No such file or directory");
    // Too short for its byteLength.
    writeBytes(dir + "/scene.bin", std::vector<unsigned char>(10));
    EXPECT_EQ(errorOf(rg::loadGltf(path)),
              "'" + path + "': buffer 0 'scene.bin': the file has 10 bytes, byteLength says " +
                  std::to_string(g.bin.size()));
}

TEST(GltfErrors, MissingOrUndecodableImage) {
    const std::string dir = tmpDir("image");
    GltfBuilder g;
    addQuad(g, true);
    g.j["images"] = json::array({{{"uri", "missing.png"}}});
    g.j["textures"] = json::array({{{"source", 0}}});
    g.j["materials"] =
        json::array({{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}});
    g.j["meshes"][0]["primitives"][0]["material"] = 0;
    g.scene({g.node({{"mesh", 0}})});
    const std::string path = g.writeGltf(dir, "i");
    EXPECT_EQ(errorOf(rg::loadGltf(path)), "'" + path + "': image 0 'missing.png': cannot open '" +
                                               dir + "/missing.png': No such file or directory");
    writeText(dir + "/missing.png", "not a png");
    EXPECT_EQ(errorOf(rg::loadGltf(path))
                  .rfind("'" + path + "': image 0 'missing.png': not a PNG or JPEG image (", 0),
              0u)
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
    g.accessor(view, kFloat, 3, "VEC3");  // ...read as three
    g.mesh("tri", json::array({{{"attributes", {{"POSITION", 0}}}}}));
    g.scene({g.node({{"mesh", 0}})});
    const std::string path = g.writeGltf(dir, "r");
    EXPECT_EQ(
        errorOf(rg::loadGltf(path)),
        "'" + path +
            "': mesh 0 'tri' primitive 0: POSITION: accessor 0 is out of range: it reads bytes "
            "0..36 of buffer view 0, which has 24 bytes");
    // A buffer view past the end of its buffer.
    g.j["bufferViews"][0]["byteLength"] = 36;
    g.j["bufferViews"][0]["byteOffset"] = 8;
    EXPECT_EQ(errorOf(rg::loadGltf(g.writeGltf(dir, "r2"))),
              "'" + dir +
                  "/r2.gltf': mesh 0 'tri' primitive 0: POSITION: accessor 0: buffer view 0 (bytes "
                  "8..44) is outside buffer 0 (36 bytes)");
    // An accessor index that does not exist.
    g.j["bufferViews"][0]["byteOffset"] = 0;
    g.j["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] = 7;
    EXPECT_EQ(
        errorOf(rg::loadGltf(g.writeGltf(dir, "r3"))),
        "'" + dir +
            "/r3.gltf': mesh 0 'tri' primitive 0: NORMAL: accessor 7 does not exist (1 accessors)");
    // A wrong accessor type.
    g.j["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] = 0;
    g.j["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] = 0;
    EXPECT_EQ(
        errorOf(rg::loadGltf(g.writeGltf(dir, "r4"))),
        "'" + dir +
            "/r4.gltf': mesh 0 'tri' primitive 0: TEXCOORD_0: accessor 0 is VEC3, expected VEC2");
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
                                               "': mesh 0 'tri' primitive 0: indices: accessor 1: "
                                               "index 5 (element 2) is out of range: "
                                               "the primitive has 3 vertices");
}

// An unknown mode and a primitive without positions are refused; LINES with an odd index count
// lose the last one with a warning. The file's other primitives still load.
TEST(GltfErrors, PrimitiveModesAndPositionsAreChecked) {
    const std::string dir = tmpDir("mode");
    GltfBuilder g;
    const int pos = g.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
    g.mesh("pts", json::array({{{"attributes", {{"POSITION", pos}}}, {"mode", 1}},
                               {{"attributes", {{"POSITION", pos}}}, {"mode", 4}}}));
    g.scene({g.node({{"mesh", 0}})});
    const std::string path = g.writeGltf(dir, "m");
    auto r = rg::loadGltf(path);
    ASSERT_TRUE(r) << errorOf(r);
    ASSERT_EQ(r->meshes[0].primitives.size(), 1u);  // the triangle
    ASSERT_EQ(r->meshes[0].lines.size(), 1u);
    EXPECT_EQ(r->meshes[0].lines[0].indices, (std::vector<uint32_t>{0, 1}));
    ASSERT_EQ(r->warnings.size(), 1u);
    EXPECT_EQ(r->warnings[0], "'" + path +
                                  "': mesh 0 'pts' primitive 0: 3 indices is not a whole number "
                                  "of segments; the last is ignored");
    g.j["meshes"][0]["primitives"][0]["mode"] = 9;
    EXPECT_EQ(
        errorOf(rg::loadGltf(g.writeGltf(dir, "m4"))),
        "'" + dir + "/m4.gltf': mesh 0 'pts' primitive 0: mode 9 is not a glTF primitive mode");
    g.j["meshes"][0]["primitives"][0].erase("mode");
    g.j["meshes"][0]["primitives"][0]["attributes"].erase("POSITION");
    g.j["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] = pos;
    EXPECT_EQ(errorOf(rg::loadGltf(g.writeGltf(dir, "m3"))),
              "'" + dir + "/m3.gltf': mesh 0 'pts' primitive 0: no POSITION attribute");
}

// Fields of the wrong type, which tinygltf would take as absent and render: each is refused with
// the file and the field's path (glTF 2.0's schema: types, counts, index signs).
TEST(GltfErrors, FieldsOfTheWrongTypeAreRefusedByTheirPath) {
    const std::string dir = tmpDir("schema");
    struct Case {
        const char* what;
        std::function<void(json&)> edit;
        std::string message;
    };
    const Case cases[] = {
        {"name", [](json& j) { j["nodes"][0]["name"] = 42; },
         "nodes[0].name: expected a string, got 42"},
        {"primitives", [](json& j) { j["meshes"][0]["primitives"] = json::object(); },
         "meshes[0].primitives: expected a non-empty array of primitives, got {}"},
        {"texture index",
         [](json& j) {
             j["materials"] =
                 json::array({{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", -1}}}}}}});
         },
         "materials[0].pbrMetallicRoughness.baseColorTexture.index: expected an index (a whole "
         "number >= 0), got -1"},
        {"scale", [](json& j) { j["nodes"][0]["scale"] = "not a number"; },
         "nodes[0].scale: expected an array of 3 numbers, got \"not a number\""},
        {"scale element",
         [](json& j) {
             j["nodes"][0]["scale"] = {1, "x", 1};
         },
         "nodes[0].scale[1]: expected a number, got \"x\""},
        {"extension",
         [](json& j) {
             j["nodes"][0]["extensions"] = {{"KHR_lights_punctual", "light 0"}};
         },
         "nodes[0].extensions.KHR_lights_punctual: expected an object, got \"light 0\""},
        {"attributes",
         [](json& j) { j["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = 0.5; },
         "meshes[0].primitives[0].attributes.POSITION: expected an index (a whole number >= 0), "
         "got 0.5"},
    };
    for (const Case& c : cases) {
        GltfBuilder g;
        addQuad(g, true);
        c.edit(g.j);
        const std::string path = g.writeGltf(dir, "bad");
        EXPECT_EQ(errorOf(rg::loadGltf(path)), "'" + path + "': " + c.message) << c.what;
    }
    GltfBuilder good;  // and the same file unedited loads
    addQuad(good, true);
    EXPECT_TRUE(rg::loadGltf(good.writeGltf(dir, "good")));
}

TEST(GltfErrors, NumbersOutsideTheirGltfRange) {
    const std::string dir = tmpDir("numbers");
    GltfBuilder g;
    g.j["materials"] =
        json::array({{{"name", "m"}, {"pbrMetallicRoughness", {{"roughnessFactor", 1.5}}}}});
    EXPECT_EQ(errorOf(rg::loadGltf(g.writeGltf(dir, "a"))),
              "'" + dir +
                  "/a.gltf': material 0 'm': roughnessFactor is 1.5, expected a number in [0, 1]");
    g.j["materials"] = json::array({{{"emissiveFactor", {1, 2, 0}}}});
    EXPECT_EQ(
        errorOf(rg::loadGltf(g.writeGltf(dir, "b"))),
        "'" + dir + "/b.gltf': material 0: emissiveFactor[1] is 2, expected a number in [0, 1]");
    g.j.erase("materials");
    g.j["extensions"]["KHR_lights_punctual"]["lights"] =
        json::array({{{"type", "spot"},
                      {"intensity", 1.0},
                      {"spot", {{"innerConeAngle", 0.9}, {"outerConeAngle", 0.5}}}}});
    g.scene({g.node({{"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}})});
    EXPECT_EQ(
        errorOf(rg::loadGltf(g.writeGltf(dir, "c"))),
        "'" + dir + "/c.gltf': light 0: spot.innerConeAngle is 0.9, expected a number in [0, 0.5]");
}

TEST(GltfErrors, NodeCycleAndBadTransforms) {
    const std::string dir = tmpDir("cycle");
    GltfBuilder g;
    g.node({{"name", "a"}, {"children", {1}}});
    g.node({{"name", "b"}, {"children", {0}}});
    g.scene({0});
    EXPECT_EQ(
        errorOf(rg::loadGltf(g.writeGltf(dir, "c"))),
        "'" + dir + "/c.gltf': node 0 'a' is its own ancestor (the node hierarchy has a cycle)");
    // A node shared by two parents.
    GltfBuilder d;
    const int shared = d.node({{"name", "s"}});
    d.scene({d.node({{"children", {shared}}}), d.node({{"children", {shared}}})});
    EXPECT_EQ(
        errorOf(rg::loadGltf(d.writeGltf(dir, "d"))),
        "'" + dir +
            "/d.gltf': node 0 's' appears twice in the hierarchy (a glTF node has one parent)");
    // A chain too deep to walk.
    GltfBuilder deep;
    for (int i = 0; i < 1100; ++i)
        deep.node(i + 1 < 1100 ? json{{"children", {i + 1}}} : json::object());
    deep.scene({0});
    EXPECT_EQ(errorOf(rg::loadGltf(deep.writeGltf(dir, "deep"))),
              "'" + dir + "/deep.gltf': the node hierarchy is deeper than 1000 levels");
    GltfBuilder h;
    h.scene({h.node({{"name", "n"}, {"rotation", {0, 0, 1}}})});
    EXPECT_EQ(
        errorOf(rg::loadGltf(h.writeGltf(dir, "r"))),
        "'" + dir + "/r.gltf': nodes[0].rotation: expected an array of 4 numbers, got [0,0,1]");
}

}  // namespace

// KHR_draco_mesh_compression (Debian's libdraco-dev): a quad's positions and normals compressed
// by Draco's own encoder decode to the same vertices and triangles as the uncompressed file; a
// buffer that is not Draco, or an attribute id the mesh lacks, is an error naming the primitive.
TEST(GltfErrors, DracoCompressedPrimitivesDecodeOrAreRefusedByName) {
    const std::string dir = tmpDir("draco");
    const glm::vec3 corners[4] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    const uint32_t faces[2][3] = {{0, 1, 2}, {0, 2, 3}};
    draco::TriangleSoupMeshBuilder builder;
    builder.Start(2);
    const int pos = builder.AddAttribute(draco::GeometryAttribute::POSITION, 3, draco::DT_FLOAT32);
    const int nrm = builder.AddAttribute(draco::GeometryAttribute::NORMAL, 3, draco::DT_FLOAT32);
    const glm::vec3 up(0, 0, 1);
    for (int f = 0; f < 2; ++f) {
        builder.SetAttributeValuesForFace(pos, draco::FaceIndex(f), &corners[faces[f][0]],
                                          &corners[faces[f][1]], &corners[faces[f][2]]);
        builder.SetAttributeValuesForFace(nrm, draco::FaceIndex(f), &up, &up, &up);
    }
    std::unique_ptr<draco::Mesh> mesh = builder.Finalize();
    ASSERT_TRUE(mesh);
    draco::Encoder encoder;
    draco::EncoderBuffer encoded;
    ASSERT_TRUE(encoder.EncodeMeshToBuffer(*mesh, &encoded).ok());
    const int posId = int(mesh->attribute(pos)->unique_id()),
              nrmId = int(mesh->attribute(nrm)->unique_id());

    auto load = [&](const std::string& name, const std::vector<char>& bytes, int positionId) {
        GltfBuilder g;
        const int view = g.view(bytes.data(), bytes.size());
        auto accessor = [&](int count, const char* type) {
            g.j["accessors"].push_back({{"componentType", 5126}, {"count", count}, {"type", type}});
            return int(g.j["accessors"].size() - 1);
        };
        const int p = accessor(int(mesh->num_points()), "VEC3"),
                  n = accessor(int(mesh->num_points()), "VEC3");
        g.j["accessors"].push_back({{"componentType", 5125}, {"count", 6}, {"type", "SCALAR"}});
        const int idx = int(g.j["accessors"].size() - 1);
        g.mesh(
            "quad",
            json::array({{{"attributes", {{"POSITION", p}, {"NORMAL", n}}},
                          {"indices", idx},
                          {"extensions",
                           {{"KHR_draco_mesh_compression",
                             {{"bufferView", view},
                              {"attributes", {{"POSITION", positionId}, {"NORMAL", nrmId}}}}}}}}}));
        g.j["extensionsUsed"] = {"KHR_draco_mesh_compression"};
        g.j["extensionsRequired"] = {"KHR_draco_mesh_compression"};
        g.scene({g.node({{"mesh", 0}})});
        rg::GltfOptions o;
        o.loadImages = false;
        o.buildLods = false;
        return rg::loadGltf(g.writeGltf(dir, name), o);
    };
    const std::vector<char> bytes(encoded.data(), encoded.data() + encoded.size());
    auto scene = load("quad", bytes, posId);
    ASSERT_TRUE(scene) << errorOf(scene);
    const rg::Primitive& prim = scene->meshes[0].primitives[0];
    ASSERT_EQ(prim.indices.size(), 6u);
    // The same two triangles (Draco may reorder faces and rotate corners, never the winding):
    // each decoded triangle, rotated to start at its lowest corner, is one of the quad's.
    auto canonical = [](std::array<glm::vec3, 3> t) {
        auto key = [](glm::vec3 p) { return p.x * 10.0f + p.y; };
        while (key(t[0]) > key(t[1]) || key(t[0]) > key(t[2]))
            std::rotate(t.begin(), t.begin() + 1, t.end());
        return t;
    };
    std::vector<std::array<glm::vec3, 3>> want, got;
    for (int f = 0; f < 2; ++f)
        want.push_back(
            canonical({corners[faces[f][0]], corners[faces[f][1]], corners[faces[f][2]]}));
    for (int f = 0; f < 2; ++f) {
        std::array<glm::vec3, 3> t;
        for (int k = 0; k < 3; ++k) {
            const rg::Vertex& v = prim.vertices[prim.indices[size_t(3 * f + k)]];
            t[size_t(k)] = v.position;
            expectNear(v.normal, up, 1e-6f, "normal");
        }
        got.push_back(canonical(t));
    }
    for (const auto& t : got)
        EXPECT_TRUE(std::find(want.begin(), want.end(), t) != want.end())
            << "a triangle the quad does not have: (" << t[0].x << ", " << t[0].y << ") (" << t[1].x
            << ", " << t[1].y << ") (" << t[2].x << ", " << t[2].y << ")";

    // The decoded primitive is kept by the content hash of the compressed bytes: the second load
    // reads it back (seen here by editing the kept file: every 1.0f becomes 2.0f); a kept file cut
    // short is not believed, the buffer is decoded anew and the file written again.
    {
        const std::string cache = dir + "/decoded";
        std::filesystem::remove_all(cache);
        rg::setGltfDecodeCacheDir(cache);
        ASSERT_TRUE(load("cached", bytes, posId));
        std::vector<std::string> files;
        for (const auto& e : std::filesystem::directory_iterator(cache))
            files.push_back(e.path().string());
        ASSERT_EQ(files.size(), 1u);
        auto kept = readBytes(files[0]);
        const size_t whole = kept.size();
        const float one = 1.0f, two = 2.0f;
        for (size_t i = 0; i + 4 <= kept.size(); i += 4)
            if (std::memcmp(&kept[i], &one, 4) == 0) std::memcpy(&kept[i], &two, 4);
        std::ofstream(files[0], std::ios::binary)
            .write(reinterpret_cast<const char*>(kept.data()), std::streamsize(kept.size()));
        auto edited = load("cached", bytes, posId);
        ASSERT_TRUE(edited) << errorOf(edited);
        float largest = 0.0f;
        for (const rg::Vertex& v : edited->meshes[0].primitives[0].vertices)
            largest = std::max({largest, v.position.x, v.position.y});
        EXPECT_EQ(largest, 2.0f) << "the kept file was not read";
        std::filesystem::resize_file(files[0], whole - 5);
        auto cut = load("cached", bytes, posId);
        ASSERT_TRUE(cut) << errorOf(cut);
        largest = 0.0f;
        for (const rg::Vertex& v : cut->meshes[0].primitives[0].vertices)
            largest = std::max({largest, v.position.x, v.position.y});
        EXPECT_EQ(largest, 1.0f) << "a file cut short was believed";
        EXPECT_EQ(std::filesystem::file_size(files[0]), whole);
        rg::setGltfDecodeCacheDir("");
    }

    std::vector<char> garbage = bytes;
    for (size_t i = 0; i < garbage.size(); i += 2) garbage[i] = char(0x5a);
    auto broken = load("garbage", garbage, posId);
    ASSERT_FALSE(broken);
    EXPECT_NE(broken.error().message.find(
                  "mesh 0 'quad' primitive 0: KHR_draco_mesh_compression: the buffer view does not "
                  "decode"),
              std::string::npos)
        << broken.error().message;
    auto missing = load("missing", bytes, 7);
    ASSERT_FALSE(missing);
    EXPECT_NE(missing.error().message.find(
                  "KHR_draco_mesh_compression.attributes.POSITION: no attribute of that id"),
              std::string::npos)
        << missing.error().message;
}

// The glTF writer (exportGlb): Lua scenes, lumens, textures, samplers and transforms round-trip
// through a .glb; the files a scene names are written relative to it. No GPU.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "scene_test_util.h"

namespace {

using rg::ErrorCode;
using namespace rg::test;

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
    EXPECT_EQ(
        warnings[0],
        "light 'softbox' (rect, nits) is not exported: KHR_lights_punctual has no area lights");

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
            for (int r = 0; r < 4; ++r)
                EXPECT_FLOAT_EQ(back->nodes[n].world[c][r], scene->nodes[n].world[c][r]);
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
        EXPECT_EQ(a.emissiveEv, b.emissiveEv) << "the emissive's unit, through extras";
        EXPECT_EQ(a.emissiveEc, b.emissiveEc);
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
    const std::string path =
        tmpDir("export_lumens") + "/lumens.glb";  // its own folder: tests run in parallel
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
    EXPECT_NEAR(lights[2]["intensity"].get<double>(),
                1000.0 / (2.0 * 3.14159265358979 * (1.0 - std::cos(0.5))), 1e-2);
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
    writeTestPng(dir + "/a.png", 2, 2,
                 {0, 0, 0, 1, 1, 1, 1, 1, 0.5f, 0.25f, 0.75f, 1, 1, 0, 0, 0.5f});
    GltfBuilder g;
    addQuad(g, true);
    g.j["images"] = json::array({{{"uri", "a.png"}}});
    g.j["samplers"] = json::array({{{"magFilter", 9728}, {"minFilter", 9986}, {"wrapS", 33648}}});
    g.j["textures"] = json::array({{{"source", 0}, {"sampler", 0}}});
    g.j["materials"] =
        json::array({{{"pbrMetallicRoughness",
                       {{"baseColorTexture",
                         {{"index", 0},
                          {"extensions",
                           {{"KHR_texture_transform",
                             {{"offset", {0.1, 0.2}}, {"rotation", 0.3}, {"scale", {2, 4}}}}}}}}}},
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
    ASSERT_EQ(back->images.size(),
              2u);  // one image, once as sRGB (base colour) and once linear (normal map)
    for (size_t i = 0; i < 2; ++i) {
        EXPECT_EQ(back->images[i].srgb, scene->images[i].srgb);
        EXPECT_EQ(back->images[i].pixels.pixels,
                  scene->images[i].pixels.pixels);  // 8-bit values survive PNG exactly
    }
    const rg::Material &a = scene->materials[0], &b = back->materials[0];
    for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r)
            EXPECT_NEAR(a.baseColorTex.transform[c][r], b.baseColorTex.transform[c][r], 1e-6f);
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
    fs::copy_file(std::string(RG_SOURCE_ROOT) + "/tests/unit/ies/downlight_2002.ies",
                  dir + "/assets/d.ies", fs::copy_options::overwrite_existing);
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
    EXPECT_EQ(fs::path(back->lights[0].ies).lexically_normal(),
              fs::path(dir + "/assets/d.ies").lexically_normal());
    ASSERT_TRUE(back->environment.has_value());
    EXPECT_EQ(fs::path(back->environment->file).lexically_normal(),
              fs::path(dir + "/assets/sky.exr").lexically_normal());
    GltfBuilder g;
    g.j["scenes"] = json::array(
        {{{"nodes", json::array()},
          {"extras",
           {{"rgraph", {{"environment", {{"kind", "hdr"}, {"file", "/etc/passwd"}}}}}}}}});
    g.j["scene"] = 0;
    auto refused = rg::loadGltf(g.writeGltf(dir, "abs"));
    ASSERT_FALSE(refused);
    EXPECT_NE(refused.error().message.find("'/etc/passwd' is an absolute path"), std::string::npos)
        << refused.error().message;
}

TEST(ExportGlb, FailedWriteLeavesNothingBehind) {
    const std::string dir = tmpDir("export_fail");
    rg::Scene empty;
    auto r = rg::exportGlb(empty, dir + "/no/such/dir/x.glb");
    ASSERT_FALSE(r);
    EXPECT_EQ(r.error().code, ErrorCode::Io);
    EXPECT_EQ(r.error().message,
              "cannot write '" + dir + "/no/such/dir/x.glb': No such file or directory");
    ASSERT_TRUE(rg::exportGlb(empty, dir + "/e.glb"));
    auto back = rg::loadGltf(dir + "/e.glb");
    ASSERT_TRUE(back) << errorOf(back);
    EXPECT_TRUE(back->nodes.empty());
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()),
              1);  // no temp file left
}

}  // namespace

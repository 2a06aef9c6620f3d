// glTF loading: the node hierarchy, primitives, generated normals and tangents, texture
// coordinates, materials and textures, alpha, lights, cameras and GLB (the material extensions in
// test_scene_gltf_extensions.cpp). No GPU.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "scene_test_util.h"

namespace {

using namespace rg::test;

// ---------------------------------------------------------------------------------------------
// glTF: structure

TEST(GltfLoad, ChildUnderTranslatedRotatedParentLandsAtTheRightWorldPosition) {
    const std::string dir = tmpDir("hierarchy");
    GltfBuilder g;
    addQuad(g, true);
    // Parent: translate (1, 2, 3), rotate +90° about Y (quaternion x, y, z, w). Child: (1, 0, 0).
    const float s = std::sqrt(0.5f);
    const int child = g.node({{"name", "child"}, {"mesh", 0}, {"translation", {1, 0, 0}}});
    const int parent = g.node({{"name", "parent"},
                               {"translation", {1, 2, 3}},
                               {"rotation", {0, s, 0, s}},
                               {"children", {child}}});
    // The same through a matrix: translate (0, 0, -5), scale 2; its child at (0, 1, 0).
    const int child2 = g.node({{"name", "child2"}, {"mesh", 0}, {"translation", {0, 1, 0}}});
    const int parent2 = g.node({{"name", "parent2"},
                                {"matrix", {2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 2, 0, 0, 0, -5, 1}},
                                {"children", {child2}}});
    g.scene({parent, parent2});
    auto scene = rg::loadGltf(g.writeGltf(dir, "h"));
    ASSERT_TRUE(scene) << errorOf(scene);
    ASSERT_EQ(scene->nodes.size(), 2u);
    EXPECT_EQ(scene->nodes[0].name, "child");
    // R_y(90°) maps +x to -z: (1, 2, 3) + (0, 0, -1).
    expectNear(origin(scene->nodes[0].world), {1, 2, 2}, 1e-5f, "child origin");
    // The quad's corner (1, 0, 0) goes to child (1,0,0)+(1,0,0) -> rotated (0,0,-2) -> (1, 2, 1).
    expectNear(glm::vec3(scene->nodes[0].world * glm::vec4(1, 0, 0, 1)), {1, 2, 1}, 1e-5f,
               "corner");
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
    g.mesh("two",
           json::array({{{"attributes", {{"POSITION", pos}, {"NORMAL", nrm}}},
                         {"indices", idx8},
                         {"material", 1}},
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
    EXPECT_EQ(prims[1].indices,
              (std::vector<uint32_t>{0, 1, 2}));  // generated for a non-indexed primitive
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
    const int pos =
        g.floats({0, 0, 0, 0, 1, 0, 1, 0, 0, 1, 1, 0}, "VEC3");  // zig-zag strip facing +Z
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
        const glm::vec3 a = strip.vertices[strip.indices[t]].position,
                        b = strip.vertices[strip.indices[t + 1]].position,
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
    g.mesh("mirrored",
           json::array({{{"attributes", {{"POSITION", pos}, {"NORMAL", nrm}, {"TEXCOORD_0", uv}}},
                         {"indices", g.indices16({0, 1, 2, 0, 2, 3})}}}));
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
            const uint32_t a = uint32_t(y * (n + 1) + x), b = a + 1, c = a + uint32_t(n + 1),
                           d = c + 1;
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
    g.mesh("fold", json::array({{{"attributes", {{"POSITION", pos}}},
                                 {"indices", g.indices16({0, 1, 2, 0, 5, 4})}}}));
    g.scene({g.node({{"mesh", 0}})});
    auto scene = rg::loadGltf(g.writeGltf(dir, "f"));
    ASSERT_TRUE(scene) << errorOf(scene);
    const auto& p = scene->meshes[0].primitives[0];
    ASSERT_EQ(p.vertices.size(), 6u);  // unwelded: each triangle its own vertices
    for (int k = 0; k < 3; ++k)
        expectNear(p.vertices[size_t(k)].normal, {0, 0, 1}, 1e-6f, "first face");
    for (int k = 3; k < 6; ++k)
        expectNear(p.vertices[size_t(k)].normal, {1, 0, 0}, 1e-6f, "second face");
    for (const auto& v : p.vertices)
        EXPECT_NEAR(glm::dot(glm::vec3(v.tangent), v.normal), 0.0f, 1e-6f);
}

TEST(GltfLoad, NormalizedIntegerTexcoordsAndSecondUvSet) {
    const std::string dir = tmpDir("uvtypes");
    GltfBuilder g;
    const int pos = g.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
    const uint8_t uvb[6] = {0, 255, 255, 255, 0, 0};
    const uint16_t uvs[6] = {0, 65535, 32768, 65535, 0, 0};
    const int uv0 = g.accessor(g.view(uvb, 6), kUByte, 3, "VEC2", true);
    const int uv1 = g.accessor(g.view(uvs, 12), kUShort, 3, "VEC2", true);
    g.mesh("m", json::array({{{"attributes",
                               {{"POSITION", pos}, {"TEXCOORD_0", uv0}, {"TEXCOORD_1", uv1}}}}}));
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
    writeTestPng(dir + "/albedo.png", 2, 1,
                 {128 / 255.0f, 128 / 255.0f, 128 / 255.0f, 1, 1, 1, 1, 1});
    writeTestPng(dir + "/data.png", 1, 1, {0.25f, 0.5f, 0.75f, 1});
    GltfBuilder g;
    addQuad(g, true);
    g.j["images"] = json::array({{{"uri", "albedo.png"}}, {{"uri", "data.png"}}});
    g.j["samplers"] = json::array(
        {{{"magFilter", 9728}, {"minFilter", 9985}, {"wrapS", 33071}, {"wrapT", 33648}}});
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
            {"extensions",
             {{"KHR_texture_transform",
               {{"offset", {0.5, 0.25}},
                {"rotation", half},
                {"scale", {2, 3}},
                {"texCoord", 1}}}}}}},
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
    expectNear(m.emissive, {100, 50, 25}, 1e-4f, "emissive = factor x strength");
    // Relative to the exposure, at the EC where a factor of 1 exposes to 1:
    // 2^(EV + EC − 3) · 1 / (1.2 · 2^EV) = 1.
    EXPECT_TRUE(m.emissiveEv);
    EXPECT_NEAR(std::exp2(m.emissiveEc - 3.0) / 1.2, 1.0, 1e-6);
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
    const glm::vec3 u =
        m.baseColorTex.transform * glm::vec3(1, 0, 1);  // S: (2,0); R(90°): (0,-2); T: (0.5,-1.75)
    EXPECT_NEAR(u.x, 0.5f, 1e-6f);
    EXPECT_NEAR(u.y, -1.75f, 1e-6f);
    const glm::vec3 v =
        m.baseColorTex.transform * glm::vec3(0, 1, 1);  // S: (0,3); R: (3,0); T: (3.5,0.25)
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
    g.j["materials"] =
        json::array({{{"name", "o"}},
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
    EXPECT_EQ(errorOf(bad),
              "'" + dir +
                  "/a2.gltf': material 1 'm': alphaMode 'CUTOUT', expected OPAQUE, MASK or BLEND");
}

TEST(GltfLoad, PunctualLightsKeepGltfUnitsAndTakeTheirNodeTransform) {
    const std::string dir = tmpDir("lights");
    GltfBuilder g;
    g.j["extensionsUsed"] = {"KHR_lights_punctual"};
    g.j["extensions"]["KHR_lights_punctual"]["lights"] =
        json::array({{{"name", "bulb"},
                      {"type", "point"},
                      {"intensity", 5.0},
                      {"color", {1, 0.5, 0.25}},
                      {"range", 10}},
                     {{"name", "spot"},
                      {"type", "spot"},
                      {"intensity", 20.0},
                      {"spot", {{"innerConeAngle", 0.2}, {"outerConeAngle", 0.6}}}},
                     {{"name", "sun"}, {"type", "directional"}, {"intensity", 3.0}}});
    const float s = std::sqrt(0.5f);
    g.scene({g.node({{"translation", {1, 2, 3}},
                     {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}}),
             g.node({{"extensions", {{"KHR_lights_punctual", {{"light", 1}}}}}}),
             // -90° about X turns -Z into -Y: the sun shines straight down.
             g.node({{"rotation", {-s, 0, 0, s}},
                     {"extensions", {{"KHR_lights_punctual", {{"light", 2}}}}}})});
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
    g.j["cameras"] =
        json::array({{{"name", "cam"},
                      {"type", "perspective"},
                      {"perspective", {{"yfov", 0.6}, {"znear", 0.1}, {"zfar", 50}}}}});
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
    g.j["cameras"] =
        json::array({{{"type", "perspective"}, {"perspective", {{"yfov", 0.6}, {"znear", 0.1}}}},
                     {{"type", "orthographic"},
                      {"orthographic", {{"xmag", 4}, {"ymag", 3}, {"znear", 0}, {"zfar", 100}}}}});
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
    EXPECT_NE(refused.error().message.find("fisheye"), std::string::npos)
        << refused.error().message;
}

TEST(GltfLoad, GlbWithAnEmbeddedImage) {
    const std::string dir = tmpDir("glb");
    writeTestPng(dir + "/t.png", 1, 1, {1, 0, 0, 1});
    auto png = readBytes(dir + "/t.png");
    GltfBuilder g;
    addQuad(g, true);
    const int view = g.view(png.data(), png.size());
    g.j["images"] =
        json::array({{{"bufferView", view}, {"mimeType", "image/png"}, {"name", "red"}}});
    g.j["textures"] = json::array({{{"source", 0}}});
    g.j["materials"] =
        json::array({{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}});
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

}  // namespace

// EXT_mesh_gpu_instancing: the node's mesh once per instance, at the node's transform times the
// instance's translation, rotation and scale; attributes of different counts are refused naming
// both. Without the extension the node is drawn once.
TEST(GltfLoad, GpuInstancingPlacesEveryInstance) {
    const std::string dir = tmpDir("instancing");
    auto build = [&](bool instanced, bool mismatched) {
        GltfBuilder g;
        addQuad(g, false);
        const int t = g.floats({1, 0, 0, 0, 2, 0, 0, 0, 3}, "VEC3");
        // Instance 1 turned 90° about +Y: (x, y, z, w) = (0, sin 45°, 0, cos 45°).
        const float h = 0.70710678f;
        const int r = g.floats({0, 0, 0, 1, 0, h, 0, h, 0, 0, 0, 1}, "VEC4");
        const int s = g.floats(mismatched ? std::vector<float>{2, 2, 2, 1, 1, 1}
                                          : std::vector<float>{2, 2, 2, 1, 1, 1, 1, 1, 1},
                               "VEC3");
        json node = {{"mesh", 0}, {"name", "tree"}, {"translation", {0, 10, 0}}};
        if (instanced) {
            node["extensions"] = {
                {"EXT_mesh_gpu_instancing",
                 {{"attributes", {{"TRANSLATION", t}, {"ROTATION", r}, {"SCALE", s}}}}}};
            g.j["extensionsUsed"] = {"EXT_mesh_gpu_instancing"};
        }
        g.scene({g.node(node)});
        rg::GltfOptions o;
        o.loadImages = false;
        return rg::loadGltf(g.writeGltf(dir, instanced ? "instanced" : "single"), o);
    };
    auto scene = build(true, false);
    ASSERT_TRUE(scene) << errorOf(scene);
    ASSERT_EQ(scene->nodes.size(), 3u);
    EXPECT_EQ(scene->nodes[1].name, "tree #1");
    // Instance 0: translated by (1, 10, 0), scaled 2: the local +X axis has length 2.
    const glm::mat4& a = scene->nodes[0].world;
    EXPECT_NEAR(a[3][0], 1.0f, 1e-6f);
    EXPECT_NEAR(a[3][1], 10.0f, 1e-6f);
    EXPECT_NEAR(a[0][0], 2.0f, 1e-6f);
    // Instance 1: at (0, 12, 0), its local +X turned onto −Z.
    const glm::mat4& b = scene->nodes[1].world;
    EXPECT_NEAR(b[3][1], 12.0f, 1e-6f);
    EXPECT_NEAR(b[0][2], -1.0f, 1e-5f);
    EXPECT_NEAR(b[0][0], 0.0f, 1e-5f);
    EXPECT_NEAR(scene->nodes[2].world[3][2], 3.0f, 1e-6f);
    // One mesh for all: the renderer draws them as instances of it (passes/scene_pass.cpp).
    EXPECT_EQ(scene->meshes.size(), 1u);
    for (const auto& n : scene->nodes) EXPECT_EQ(n.mesh, 0);
    EXPECT_TRUE(scene->warnings.empty()) << scene->warnings[0];

    auto single = build(false, false);
    ASSERT_TRUE(single) << errorOf(single);
    EXPECT_EQ(single->nodes.size(), 1u);

    auto bad = build(true, true);
    ASSERT_FALSE(bad);
    EXPECT_NE(bad.error().message.find("SCALE has 2 instances, the attributes before it 3"),
              std::string::npos)
        << bad.error().message;
}

// KHR_materials_variants: with a variant chosen by name (GltfOptions::variant, --variant, the Lua
// scene.gltf's `variant`) each primitive takes the material its mappings give that variant, the
// others keep their own; without one, the file's defaults; a name the file lacks is refused with
// the names it has.
TEST(GltfLoad, MaterialVariantsPickEachPrimitivesMaterial) {
    const std::string dir = tmpDir("variants");
    GltfBuilder g;
    addQuad(g, false);
    g.j["materials"] = json::array(
        {{{"name", "plain"}},
         {{"name", "red"}, {"pbrMetallicRoughness", {{"baseColorFactor", {1, 0, 0, 1}}}}},
         {{"name", "blue"}, {"pbrMetallicRoughness", {{"baseColorFactor", {0, 0, 1, 1}}}}}});
    g.j["meshes"][0]["primitives"][0]["material"] = 0;
    g.j["meshes"][0]["primitives"][0]["extensions"] = {
        {"KHR_materials_variants",
         {{"mappings",
           {{{"material", 1}, {"variants", {0}}}, {{"material", 2}, {"variants", {1}}}}}}}};
    g.j["extensions"] = {
        {"KHR_materials_variants", {{"variants", {{{"name", "rust"}}, {{"name", "sea"}}}}}}};
    g.j["extensionsUsed"] = {"KHR_materials_variants"};
    g.scene({g.node({{"mesh", 0}})});
    const std::string file = g.writeGltf(dir, "variants");
    auto materialOf = [&](const std::string& variant) -> std::string {
        rg::GltfOptions o;
        o.loadImages = false;
        o.variant = variant;
        auto scene = rg::loadGltf(file, o);
        if (!scene) return "error: " + scene.error().message;
        return scene->materials[scene->meshes[0].primitives[0].material].name;
    };
    EXPECT_EQ(materialOf(""), "plain");
    EXPECT_EQ(materialOf("rust"), "red");
    EXPECT_EQ(materialOf("sea"), "blue");
    const std::string bad = materialOf("gold");
    EXPECT_NE(bad.find("material variant 'gold' is not in the file (its variants: 'rust', 'sea')"),
              std::string::npos)
        << bad;
}

// KHR_texture_basisu (KTX2) has no Debian decoder: a texture with a plain fallback image uses it
// and says so once; one with only the KTX2 image is left out with a warning naming why; a file
// that requires the extension stays refused (GltfErrors.RequiredUnsupportedExtensionIsRefusedByName).
TEST(GltfLoad, BasisuTexturesFallBackToTheirPlainImageWithAWarning) {
    const std::string dir = tmpDir("basisu");
    GltfBuilder g;
    addQuad(g, true);
    g.j["images"] = json::array({{{"uri", "albedo.png"}}, {{"uri", "albedo.ktx2"}}});
    g.j["textures"] =
        json::array({{{"source", 0}, {"extensions", {{"KHR_texture_basisu", {{"source", 1}}}}}},
                     {{"extensions", {{"KHR_texture_basisu", {{"source", 1}}}}}}});
    g.j["materials"] = json::array(
        {{{"name", "fallback"}, {"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}},
         {{"name", "ktx2_only"},
          {"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 1}}}}}}});
    g.j["meshes"][0]["primitives"][0]["material"] = 0;
    g.j["extensionsUsed"] = {"KHR_texture_basisu"};
    g.scene({g.node({{"mesh", 0}})});
    rg::GltfOptions o;
    o.loadImages = false;
    auto scene = rg::loadGltf(g.writeGltf(dir, "basisu"), o);
    ASSERT_TRUE(scene) << errorOf(scene);
    const auto material = [&](const std::string& name) {
        for (const auto& m : scene->materials)
            if (m.name == name) return m;
        return rg::Material{};
    };
    EXPECT_TRUE(material("fallback").baseColorTex.valid());
    EXPECT_FALSE(material("ktx2_only").baseColorTex.valid());
    std::string all;
    for (const auto& w : scene->warnings) all += w + "\n";
    EXPECT_NE(all.find("texture 0: KHR_texture_basisu's KTX2 image cannot be decoded here; its "
                       "fallback image 0 is used"),
              std::string::npos)
        << all;
    EXPECT_NE(all.find("texture 1 is KHR_texture_basisu only (KTX2, which rgraph cannot decode) "
                       "and has no PNG/JPEG fallback; ignored"),
              std::string::npos)
        << all;
}

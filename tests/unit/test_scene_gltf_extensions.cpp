// glTF material extensions: KHR_materials_ior, _specular, _clearcoat, _sheen, _transmission,
// _volume, _unlit and _pbrSpecularGlossiness onto rgraph's material models (graph/scene/gltf_load_materials.cpp). No GPU.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "scene_test_util.h"

namespace {
using namespace rg::test;

// KHR_materials_ior and _specular set the standard material's reflectance (f0 = 0.16 r²), and
// KHR_materials_clearcoat makes it the pipeline's clear_coat material, its textures (the coat's
// normal map too) the model's own; what rgraph cannot hold (a coloured specular, a coated base's
// IOR) is named in a warning.
TEST(GltfLoad, IorSpecularAndClearcoatExtensionsMapOntoTheMaterials) {
    const std::string dir = tmpDir("material_ext");
    GltfBuilder g;
    addQuad(g, true);
    g.j["materials"] =
        json::array({{{"name", "plain"}},
                     {{"name", "water"}, {"extensions", {{"KHR_materials_ior", {{"ior", 1.33}}}}}},
                     {{"name", "dim"},
                      {"extensions",
                       {{"KHR_materials_specular",
                         {{"specularFactor", 0.5}, {"specularColorFactor", {1.0, 0.5, 0.0}}}}}}},
                     {{"name", "gem"}, {"extensions", {{"KHR_materials_ior", {{"ior", 2.4}}}}}},
                     {{"name", "car"},
                      {"extensions",
                       {{"KHR_materials_clearcoat",
                         {{"clearcoatFactor", 0.8},
                          {"clearcoatRoughnessFactor", 0.1},
                          {"clearcoatTexture", {{"index", 0}, {"texCoord", 1}}},
                          {"clearcoatRoughnessTexture",
                           {{"index", 1},
                            {"extensions", {{"KHR_texture_transform", {{"scale", {2.0, 4.0}}}}}}}},
                          {"clearcoatNormalTexture", {{"index", 0}, {"scale", 0.5}}}}},
                        {"KHR_materials_ior", {{"ior", 1.33}}}}}},
                     {{"name", "nocoat"},
                      {"extensions", {{"KHR_materials_clearcoat", {{"clearcoatFactor", 0.0}}}}}}});
    g.j["images"] = json::array({{{"uri", "coat.png"}}, {{"uri", "rough.png"}}});
    g.j["textures"] = json::array({{{"source", 0}}, {{"source", 1}}});
    g.j["extensionsUsed"] = {"KHR_materials_ior", "KHR_materials_specular",
                             "KHR_materials_clearcoat", "KHR_texture_transform"};
    g.scene({g.node({{"mesh", 0}})});
    rg::GltfOptions o;
    o.loadImages = false;
    auto scene = rg::loadGltf(g.writeGltf(dir, "e"), o);
    ASSERT_TRUE(scene) << errorOf(scene);
    const std::vector<std::string>& warnings = scene->warnings;
    const auto& m = scene->materials;
    auto f0 = [](const rg::Material& x) { return 0.16 * x.reflectance * x.reflectance; };
    EXPECT_NEAR(f0(m[0]), 0.04, 1e-6);                        // ior 1.5
    EXPECT_NEAR(f0(m[1]), std::pow(0.33 / 2.33, 2.0), 1e-6);  // water: 2 %
    EXPECT_NEAR(f0(m[2]), 0.04 * 0.5 * 0.5, 1e-6);            // × 0.5 × mean colour 0.5
    EXPECT_NEAR(f0(m[3]), 0.16, 1e-6);                        // 17 % held at 16 %
    EXPECT_EQ(m[4].model, "clear_coat");
    EXPECT_NEAR(m[4].extra["coatStrength"].asNumber(), 0.8, 1e-6);
    EXPECT_NEAR(m[4].extra["coatSmoothness"].asNumber(), 0.9, 1e-6);
    EXPECT_NEAR(m[4].extra["coatNormalScale"].asNumber(), 0.5, 1e-6);
    EXPECT_NEAR(f0(m[4]), 0.04, 1e-6);  // the clear coat layout's base f0
    // Its textures as the clear-coat model's own (materials/clearcoat.lua), linear, each with its
    // set and transform.
    ASSERT_EQ(m[4].textures.size(), 3u);
    EXPECT_TRUE(m[4].textures.at("coatNormalMap").valid());
    const rg::TextureRef& coat = m[4].textures.at("coatStrengthMap");
    const rg::TextureRef& rough = m[4].textures.at("coatRoughnessMap");
    ASSERT_TRUE(coat.valid() && rough.valid());
    EXPECT_EQ(scene->images[size_t(coat.image)].name.find("coat"), 0u);
    EXPECT_FALSE(scene->images[size_t(coat.image)].srgb);
    EXPECT_EQ(coat.texCoord, 1u);  // TEXCOORD_1, in its own slot
    EXPECT_EQ(rough.transform[0][0], 2.0f);
    EXPECT_EQ(rough.transform[1][1], 4.0f);
    EXPECT_EQ(m[5].model, "standard");  // a coat of 0 is no coat
    ASSERT_EQ(warnings.size(), 3u);
    EXPECT_NE(warnings[0].find("material 2 'dim': KHR_materials_specular.specularColorFactor is "
                               "coloured"),
              std::string::npos)
        << warnings[0];
    EXPECT_NE(warnings[1].find("material 3 'gem': f0 0.1695"), std::string::npos) << warnings[1];
    EXPECT_NE(warnings[2].find("material 4 'car': the clear coat material keeps the base's f0 at "
                               "4 %"),
              std::string::npos)
        << warnings[2];
}

// KHR_materials_sheen makes a material the pipeline's sheen material (materials/sheen.lua): its
// factors as the model's parameters, its textures as the model's own (the colour sRGB, the
// roughness linear); a black sheen is none; beside a clear coat, or over an IOR it cannot keep,
// a warning says what is dropped; an unlit material keeps none; a factor out of range is refused
// naming the JSON path.
TEST(GltfLoad, SheenMakesTheSheenMaterial) {
    const std::string dir = tmpDir("sheen");
    GltfBuilder g;
    addQuad(g, true);
    const json velvet = {{"sheenColorFactor", {0.9, 0.5, 0.2}},
                         {"sheenRoughnessFactor", 0.4},
                         {"sheenColorTexture", {{"index", 0}}},
                         {"sheenRoughnessTexture", {{"index", 1}, {"texCoord", 1}}}};
    g.j["materials"] =
        json::array({{{"name", "velvet"}, {"extensions", {{"KHR_materials_sheen", velvet}}}},
                     {{"name", "black"},
                      {"extensions", {{"KHR_materials_sheen", {{"sheenRoughnessFactor", 0.5}}}}}},
                     {{"name", "both"},
                      {"extensions",
                       {{"KHR_materials_clearcoat", {{"clearcoatFactor", 1.0}}},
                        {"KHR_materials_sheen", {{"sheenColorFactor", {1.0, 1.0, 1.0}}}}}}},
                     {{"name", "water"},
                      {"extensions",
                       {{"KHR_materials_ior", {{"ior", 1.33}}},
                        {"KHR_materials_sheen", {{"sheenColorFactor", {1.0, 1.0, 1.0}}}}}}},
                     {{"name", "flat"},
                      {"extensions",
                       {{"KHR_materials_unlit", json::object()},
                        {"KHR_materials_sheen", {{"sheenColorFactor", {1.0, 1.0, 1.0}}}}}}}});
    g.j["images"] = json::array({{{"uri", "tint.png"}}, {{"uri", "fuzz.png"}}});
    g.j["textures"] = json::array({{{"source", 0}}, {{"source", 1}}});
    g.j["extensionsUsed"] = {"KHR_materials_sheen", "KHR_materials_clearcoat", "KHR_materials_ior",
                             "KHR_materials_unlit"};
    g.scene({g.node({{"mesh", 0}})});
    rg::GltfOptions o;
    o.loadImages = false;
    auto scene = rg::loadGltf(g.writeGltf(dir, "s"), o);
    ASSERT_TRUE(scene) << errorOf(scene);
    const auto& m = scene->materials;
    EXPECT_EQ(m[0].model, "sheen");
    EXPECT_NEAR(m[0].extra["sheenColorR"].asNumber(), 0.9, 1e-6);
    EXPECT_NEAR(m[0].extra["sheenColorG"].asNumber(), 0.5, 1e-6);
    EXPECT_NEAR(m[0].extra["sheenColorB"].asNumber(), 0.2, 1e-6);
    EXPECT_NEAR(m[0].extra["sheenRoughnessFactor"].asNumber(), 0.4, 1e-6);
    ASSERT_EQ(m[0].textures.size(), 2u);
    const rg::TextureRef& tint = m[0].textures.at("sheenColorMap");
    const rg::TextureRef& fuzz = m[0].textures.at("sheenRoughnessMap");
    ASSERT_TRUE(tint.valid() && fuzz.valid());
    EXPECT_TRUE(scene->images[size_t(tint.image)].srgb);
    EXPECT_FALSE(scene->images[size_t(fuzz.image)].srgb);
    EXPECT_EQ(fuzz.texCoord, 1u);
    EXPECT_EQ(m[1].model, "standard");  // a black sheen is no sheen
    EXPECT_EQ(m[2].model, "clear_coat");
    EXPECT_EQ(m[3].model, "sheen");
    EXPECT_NEAR(m[3].reflectance, 0.5, 1e-6);  // f0 4 %, the sheen layout's
    EXPECT_EQ(m[4].model, "standard");         // unlit: nothing reflects, no sheen either
    EXPECT_TRUE(m[4].textures.empty());
    ASSERT_EQ(scene->warnings.size(), 2u);
    EXPECT_NE(scene->warnings[0].find("material 2 'both': KHR_materials_sheen is ignored: the "
                                      "material is already a 'clear_coat'"),
              std::string::npos)
        << scene->warnings[0];
    EXPECT_NE(scene->warnings[1].find("material 3 'water': the sheen material keeps f0 at 4 %"),
              std::string::npos)
        << scene->warnings[1];

    g.j["materials"][0]["extensions"]["KHR_materials_sheen"]["sheenRoughnessFactor"] = 1.5;
    auto bad = rg::loadGltf(g.writeGltf(dir, "s2"), o);
    EXPECT_NE(errorOf(bad).find("material 0 'velvet': KHR_materials_sheen.sheenRoughnessFactor"),
              std::string::npos)
        << errorOf(bad);
}

// KHR_materials_transmission (and _volume) make the pipeline's transmission material, blended
// (the forward pass draws it over the opaque frame it refracts), with its factors as params and
// its textures as the model's own; without the extension the same material is an opaque standard.
TEST(GltfLoad, TransmissionMakesTheTransmissionMaterial) {
    const std::string dir = tmpDir("transmission");
    GltfBuilder g;
    addQuad(g, true);
    const json glass = {{"transmissionFactor", 0.9}, {"transmissionTexture", {{"index", 0}}}};
    const json volume = {{"thicknessFactor", 0.25},
                         {"thicknessTexture", {{"index", 1}, {"texCoord", 1}}},
                         {"attenuationDistance", 0.5},
                         {"attenuationColor", {0.9, 0.6, 0.3}}};
    g.j["materials"] = json::array(
        {{{"name", "bottle"},
          {"alphaMode", "MASK"},
          {"extensions",
           {{"KHR_materials_transmission", glass},
            {"KHR_materials_volume", volume},
            {"KHR_materials_ior", {{"ior", 1.33}}}}}},
         {{"name", "pane"},
          {"extensions", {{"KHR_materials_transmission", {{"transmissionFactor", 1.0}}}}}},
         {{"name", "none"},
          {"extensions",
           {{"KHR_materials_transmission", {{"transmissionTexture", {{"index", 0}}}}}}}},
         {{"name", "coated"},
          {"extensions",
           {{"KHR_materials_transmission", {{"transmissionFactor", 1.0}}},
            {"KHR_materials_clearcoat", {{"clearcoatFactor", 1.0}}}}}},
         {{"name", "lonely"},
          {"extensions", {{"KHR_materials_volume", {{"thicknessFactor", 1.0}}}}}}});
    g.j["images"] = json::array({{{"uri", "clear.png"}}, {{"uri", "thick.png"}}});
    g.j["textures"] = json::array({{{"source", 0}}, {{"source", 1}}});
    g.j["extensionsUsed"] = {"KHR_materials_transmission", "KHR_materials_volume",
                             "KHR_materials_ior", "KHR_materials_clearcoat"};
    // The bottle drawn at twice and three times its mesh's size: the thickness, in the mesh's
    // space, becomes the first node's in the world's.
    g.j["meshes"][0]["primitives"][0]["material"] = 0;
    g.scene(
        {g.node({{"mesh", 0}, {"scale", {2, 2, 2}}}), g.node({{"mesh", 0}, {"scale", {3, 3, 3}}})});
    rg::GltfOptions o;
    o.loadImages = false;
    auto scene = rg::loadGltf(g.writeGltf(dir, "s"), o);
    ASSERT_TRUE(scene) << errorOf(scene);
    const auto& m = scene->materials;
    EXPECT_EQ(m[0].model, "transmission");
    EXPECT_EQ(m[0].alphaMode, rg::AlphaMode::Blend);
    EXPECT_NEAR(m[0].extra["transmissionFactor"].asNumber(), 0.9, 1e-6);
    EXPECT_NEAR(m[0].extra["thicknessFactor"].asNumber(), 0.5, 1e-6);  // 0.25 × 2
    EXPECT_NEAR(m[0].extra["attenuationDistance"].asNumber(), 0.5, 1e-6);
    EXPECT_NEAR(m[0].extra["attenuationColorR"].asNumber(), 0.9, 1e-6);
    EXPECT_NEAR(m[0].extra["attenuationColorB"].asNumber(), 0.3, 1e-6);
    // IOR 1.33: f0 = (0.33 / 2.33)² = 0.16 r².
    EXPECT_NEAR(0.16 * m[0].reflectance * m[0].reflectance, std::pow(0.33 / 2.33, 2.0), 1e-5);
    ASSERT_EQ(m[0].textures.size(), 2u);
    EXPECT_TRUE(m[0].textures.at("transmissionMap").valid());
    EXPECT_EQ(m[0].textures.at("thicknessMap").texCoord, 1u);
    EXPECT_EQ(m[1].model, "transmission");  // thin-walled: no volume
    EXPECT_NEAR(m[1].extra["thicknessFactor"].asNumber(), 0.0, 1e-9);
    EXPECT_NEAR(m[1].extra["attenuationDistance"].asNumber(), 0.0, 1e-9);  // 0: glTF's +∞
    EXPECT_EQ(m[2].model, "standard");  // a factor of 0 (× the texture): no transmission
    EXPECT_EQ(m[2].alphaMode, rg::AlphaMode::Opaque);
    EXPECT_EQ(m[3].model, "transmission");  // one model a material: the transmission first
    EXPECT_EQ(m[4].model, "standard");
    ASSERT_EQ(scene->warnings.size(), 4u);
    EXPECT_NE(scene->warnings[0].find("material 0 'bottle': alphaMode MASK on a transmission is "
                                      "drawn blended"),
              std::string::npos)
        << scene->warnings[0];
    EXPECT_NE(scene->warnings[1].find("material 3 'coated': KHR_materials_clearcoat is ignored: "
                                      "the material is already a 'transmission'"),
              std::string::npos)
        << scene->warnings[1];
    EXPECT_NE(scene->warnings[2].find("material 4 'lonely': KHR_materials_volume is ignored "
                                      "without KHR_materials_transmission"),
              std::string::npos)
        << scene->warnings[2];
    EXPECT_NE(scene->warnings[3].find("material 'bottle': KHR_materials_volume's thickness is "
                                      "scaled by its first node's scale 2"),
              std::string::npos)
        << scene->warnings[3];

    g.j["materials"][0]["extensions"]["KHR_materials_volume"]["attenuationDistance"] = 0;
    auto bad = rg::loadGltf(g.writeGltf(dir, "s2"), o);
    EXPECT_NE(errorOf(bad).find("material 0 'bottle': KHR_materials_volume.attenuationDistance"),
              std::string::npos)
        << errorOf(bad);
    g.j["materials"][0]["extensions"]["KHR_materials_volume"].erase("attenuationDistance");
    g.j["materials"][0]["extensions"]["KHR_materials_transmission"]["transmissionFactor"] = "1";
    auto wrong = rg::loadGltf(g.writeGltf(dir, "s3"), o);
    EXPECT_NE(errorOf(wrong).find("KHR_materials_transmission.transmissionFactor"),
              std::string::npos)
        << errorOf(wrong);
}

// KHR_materials_unlit: the base colour becomes emission relative to the exposure (as glTF's
// emissive), the surface reflects nothing; without the extension the same material is lit.
TEST(GltfLoad, UnlitShowsItsBaseColourAsEmission) {
    const std::string dir = tmpDir("unlit");
    for (bool unlit : {true, false}) {
        GltfBuilder g;
        addQuad(g, true);
        json m = {{"name", "label"},
                  {"pbrMetallicRoughness",
                   {{"baseColorFactor", {0.8, 0.4, 0.2, 0.5}}, {"metallicFactor", 1.0}}}};
        if (unlit) m["extensions"] = {{"KHR_materials_unlit", json::object()}};
        g.j["materials"] = json::array({m});
        if (unlit) g.j["extensionsUsed"] = {"KHR_materials_unlit"};
        g.scene({g.node({{"mesh", 0}})});
        rg::GltfOptions o;
        o.loadImages = false;
        auto scene = rg::loadGltf(g.writeGltf(dir, unlit ? "unlit" : "lit"), o);
        ASSERT_TRUE(scene) << errorOf(scene);
        const rg::Material& x = scene->materials[0];
        EXPECT_TRUE(scene->warnings.empty()) << scene->warnings[0];
        EXPECT_FLOAT_EQ(x.opacity, 0.5f);
        if (unlit) {
            EXPECT_EQ(x.emissive, glm::vec3(0.8f, 0.4f, 0.2f));
            EXPECT_TRUE(x.emissiveEv);
            EXPECT_FLOAT_EQ(x.emissiveEc, rg::kGltfEmissiveEc);
            EXPECT_EQ(x.baseColor, glm::vec3(0.0f));
            EXPECT_EQ(x.metalMask, 0.0f);
            EXPECT_EQ(x.reflectance, 0.0f);
        } else {
            EXPECT_EQ(x.emissive, glm::vec3(0.0f));
            EXPECT_EQ(x.baseColor, glm::vec3(0.8f, 0.4f, 0.2f));
            EXPECT_EQ(x.metalMask, 1.0f);
        }
    }
}

// KHR_materials_pbrSpecularGlossiness becomes the two-colour material (seed 000 tbl:3): its diffuse
// and specular colours, glossiness as smoothness, its specular-glossiness texture (sRGB) the
// model's own specularGlossinessMap. Without the extension the same material is the standard one.
TEST(GltfLoad, SpecularGlossinessBecomesTheTwoColourMaterial) {
    const std::string dir = tmpDir("specgloss");
    GltfBuilder g;
    addQuad(g, true);
    g.j["materials"] = json::array({{{"name", "oxide"},
                                     {"extensions",
                                      {{"KHR_materials_pbrSpecularGlossiness",
                                        {{"diffuseFactor", {0.3, 0.2, 0.1, 0.75}},
                                         {"specularFactor", {0.6, 0.5, 0.2}},
                                         {"glossinessFactor", 0.4},
                                         {"specularGlossinessTexture", {{"index", 0}}}}}}}},
                                    {{"name", "plain"}}});
    g.j["extensionsUsed"] = {"KHR_materials_pbrSpecularGlossiness"};
    g.j["images"] = json::array({{{"uri", "sg.png"}}});
    g.j["textures"] = json::array({{{"source", 0}}});
    g.scene({g.node({{"mesh", 0}})});
    rg::GltfOptions o;
    o.loadImages = false;
    auto scene = rg::loadGltf(g.writeGltf(dir, "sg"), o);
    ASSERT_TRUE(scene) << errorOf(scene);
    const rg::Material& x = scene->materials[0];
    EXPECT_EQ(x.model, "two_colour");
    EXPECT_EQ(x.diffuseColor, glm::vec3(0.3f, 0.2f, 0.1f));
    EXPECT_EQ(x.f0, glm::vec3(0.6f, 0.5f, 0.2f));
    EXPECT_FLOAT_EQ(x.smoothness, 0.4f);
    EXPECT_FLOAT_EQ(x.opacity, 0.75f);
    EXPECT_EQ(scene->materials[1].model, "standard");
    ASSERT_EQ(x.textures.size(), 1u);
    const rg::TextureRef& sg = x.textures.at("specularGlossinessMap");
    ASSERT_TRUE(sg.valid());
    EXPECT_TRUE(scene->images[size_t(sg.image)].srgb);
    EXPECT_TRUE(scene->warnings.empty()) << scene->warnings[0];
}

}  // namespace

// Lua scene scripts: the shipped scenes, the schema errors of objects, materials, lights,
// cameras, environments and probes with their exact text, texture files, merged glTF. No GPU.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "scene_test_util.h"

namespace {

using rg::ErrorCode;
using namespace rg::test;

// ---------------------------------------------------------------------------------------------
// Lua scene scripts

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
    const rg::Material& m =
        scene->materials[scene->meshes[size_t(corner.mesh)].primitives[0].material];
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
    expectNear(scene->lights[2].direction, glm::normalize(glm::vec3(0, -2.5f, 2)), 1e-6f,
               "rect aims at its target");

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
    EXPECT_EQ(lua.error("scene.sphere \"ball\" { radius = -1 }"),
              "bad.lua:1: scene.sphere.ball.radius: expected a number > 0, got -1");
    EXPECT_EQ(lua.error("scene.sphere \"ball\" { radius = \"big\" }"),
              "bad.lua:1: scene.sphere.ball.radius: expected a number > 0, got \"big\"");
    EXPECT_EQ(lua.error("\nscene.sphere \"ball\" { radus = 1 }"),
              "bad.lua:2: scene.sphere.ball.radus: unknown field (did you mean 'radius'?); "
              "expected one of: 'position', 'rotation', "
              "'scale', 'material', 'cast_shadows', 'doc', 'path', 'radius', 'segments'");
    EXPECT_EQ(
        lua.error("scene.sphere \"ball\" { segments = 2.5 }"),
        "bad.lua:1: scene.sphere.ball.segments: expected a whole number in [3, 1024], got 2.5");
    EXPECT_EQ(lua.error("scene.box \"b\" { size = { 1, 0, 1 } }"),
              "bad.lua:1: scene.box.b.size: expected {x, y, z} in metres with each value > 0, got "
              "{1, 0, 1}");
    EXPECT_EQ(lua.error("scene.plane \"p\" { size = 3 }"),
              "bad.lua:1: scene.plane.p.size: expected {width, depth} in metres with each value > "
              "0, got 3");
    EXPECT_EQ(lua.error("scene.box \"b\" { position = { 1, 2 } }"),
              "bad.lua:1: scene.box.b.position: expected {x, y, z} (3 numbers), got {1, 2}");
    EXPECT_EQ(
        lua.error("scene.box \"b\" { scale = 0 }"),
        "bad.lua:1: scene.box.b.scale: expected a number > 0 or {x, y, z} of numbers > 0, got 0");
    EXPECT_EQ(lua.error("scene.material \"red\" {}\nscene.sphere \"ball\" { material = \"redd\" }"),
              "bad.lua:2: scene.sphere.ball.material: unknown material 'redd' (did you mean "
              "'red'?); declared: 'red'");
    EXPECT_EQ(lua.error("scene.sphere \"ball\" { material = \"red\" }"),
              "bad.lua:1: scene.sphere.ball.material: unknown material 'red'; the scene declares "
              "no scene.material");
    EXPECT_EQ(lua.error("scene.sphere \"a\" {}\nscene.box \"a\" {}"),
              "bad.lua:2: scene.box.a: scene.sphere 'a' is already declared (at bad.lua:1)");
    EXPECT_EQ(lua.error("scene.sphere \"a\" { 1, radius = 2 }"),
              "bad.lua:1: scene.sphere.a: unexpected positional value 1; expected named fields: "
              "'position', 'rotation', 'scale', "
              "'material', 'cast_shadows', 'doc', 'path', 'radius', 'segments'");
    EXPECT_EQ(lua.error("scene.box \"b\" { cast_shadows = 0 }"),
              "bad.lua:1: scene.box.b.cast_shadows: expected a boolean, got 0");
    EXPECT_EQ(lua.error("scene.sphere \"a\" { 1, 2 }"),
              "bad.lua:1: scene.sphere.a: expected a table of fields after scene.sphere \"a\", got "
              "{1, 2}");
    EXPECT_EQ(lua.error("rg.pass \"gbuffer\" {}"),
              "bad.lua:1: rg.pass \"gbuffer\" belongs in a pipeline script, not in a scene");
    EXPECT_EQ(lua.error("scene.gltf \"g\" { file = \"nope.glb\" }"),
              "bad.lua:1: scene.gltf.g.file: cannot open '" + lua.dir +
                  "/nope.glb': No such file or directory");
    EXPECT_EQ(lua.error("scene.gltf \"g\" {}"),
              "bad.lua:1: scene.gltf.g.file: missing (expected a .gltf or .glb file, relative to "
              "the script)");
}

TEST(SceneScript, MaterialFieldErrors) {
    ScriptRunner lua("materials");
    EXPECT_EQ(lua.error("scene.material \"red\" { base_color = { 1, 2, 0 } }"),
              "bad.lua:1: scene.material.red.base_color: expected {r, g, b} with each value in [0, "
              "1], got {1, 2, 0}");
    EXPECT_EQ(lua.error("scene.material \"red\" { smoothness = 1.5 }"),
              "bad.lua:1: scene.material.red.smoothness: expected a number in [0, 1], got 1.5");
    EXPECT_EQ(lua.error("scene.material \"red\" { emissive = { -1, 0, 0 } }"),
              "bad.lua:1: scene.material.red.emissive: expected {r, g, b} with each value >= 0, "
              "got {-1, 0, 0}");
    EXPECT_EQ(lua.error("scene.material \"red\" { alpha = \"opaq\" }"),
              "bad.lua:1: scene.material.red.alpha: unknown alpha mode 'opaq' (did you mean "
              "'opaque'?); expected one of: 'opaque', "
              "'mask', 'blend'");
    EXPECT_EQ(lua.error("scene.material \"red\" { alpha_cutoff = 0.5 }"),
              "bad.lua:1: scene.material.red.alpha_cutoff: applies to alpha = \"mask\" only");
    EXPECT_EQ(lua.error("scene.material \"red\" { f0 = { 0.5, 0.5, 0.5 } }"),
              "bad.lua:1: scene.material.red.f0: applies to model 'two_colour' only (this "
              "material's model is 'standard')");
    EXPECT_EQ(
        lua.error("scene.material \"rust\" { model = \"two_colour\", base_color = { 1, 0, 0 } }"),
        "bad.lua:1: scene.material.rust.base_color: not used by model 'two_colour', which takes "
        "diffuse_color and f0");
    EXPECT_EQ(lua.error("scene.material \"red\" { params = 3 }"),
              "bad.lua:1: scene.material.red.params: expected a table of named parameters, got 3");
    EXPECT_EQ(lua.error("scene.material \"red\" { double_sided = 1 }"),
              "bad.lua:1: scene.material.red.double_sided: expected a boolean, got 1");
    EXPECT_EQ(lua.error("scene.material \"red\" { metalness = 1 }"),
              "bad.lua:1: scene.material.red.metalness: unknown field; expected one of: 'model', "
              "'base_color', 'smoothness', "
              "'metal_mask', 'reflectance', 'ao', 'emissive', 'emissive_unit', 'emissive_ec', "
              "'opacity', 'diffuse_color', 'f0', "
              "'params', 'double_sided', 'alpha', "
              "'alpha_cutoff', 'base_color_map', 'metallic_roughness_map', 'normal_map', "
              "'normal_scale', 'occlusion_map', "
              "'emissive_map', 'textures', 'doc'");
    EXPECT_EQ(lua.error("scene.material \"red\" { textures = 3 }"),
              "bad.lua:1: scene.material.red.textures: expected a table of texture files by the "
              "names the model declares, got 3");
}

TEST(SceneScript, MaterialTextureFiles) {
    // The five glTF maps from files next to the script: decoded once per file and encoding,
    // base colour and emissive sRGB, the others linear; errors name the field and the file.
    ScriptRunner lua("textures");
    rg::Image checker(2, 2, 3);
    for (uint32_t y = 0; y < 2; ++y)
        for (uint32_t x = 0; x < 2; ++x)
            for (uint32_t c = 0; c < 3; ++c)
                checker.at(x, y, c) = (x + y) % 2 ? 1.0f : (c == 0 ? 0.8f : 0.2f);
    ASSERT_TRUE(rg::writePng(lua.dir + "/checker.png", checker));
    writeText(lua.dir + "/broken.png", "not a png");
    auto ok = lua.run(
        "ok.lua",
        "scene.material \"tiles\" { base_color_map = \"checker.png\", normal_map = "
        "\"checker.png\", normal_scale = 0.5,\n"
        "                           emissive_map = \"checker.png\", emissive = { 1, 1, 1 } }\n"
        "scene.material \"more\" { base_color_map = \"checker.png\", occlusion_map = "
        "\"checker.png\" }\n"
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
              "bad.lua:1: scene.material.m.base_color_map: cannot open '" + lua.dir +
                  "/nope.png': No such file or directory");
    EXPECT_EQ(lua.error("scene.material \"m\" { normal_map = \"broken.png\" }")
                  .rfind("bad.lua:1: scene.material.m.normal_map: cannot decode '" + lua.dir +
                             "/broken.png': ",
                         0),
              0u);
    EXPECT_EQ(lua.error("scene.material \"m\" { normal_scale = 2 }"),
              "bad.lua:1: scene.material.m.normal_scale: applies with a normal_map only");
}

TEST(SceneScript, LightFieldErrorsAndUnitsPerType) {
    ScriptRunner lua("lights");
    EXPECT_EQ(
        lua.error("scene.light \"key\" { type = \"point\", intensity = 100, unit = \"lux\" }"),
        "bad.lua:1: scene.light.key.unit: a point light cannot be given in 'lux' (seed 000 tbl:8); "
        "expected 'lm', 'cd'");
    EXPECT_EQ(lua.error("scene.light \"sun\" { type = \"sun\", intensity = 100, unit = \"lm\", "
                        "direction = { 0, -1, 0 } }"),
              "bad.lua:1: scene.light.sun.unit: a sun light cannot be given in 'lm' (seed 000 "
              "tbl:8); expected 'lux'");
    EXPECT_EQ(lua.error("scene.light \"a\" { type = \"sphere\", intensity = 100, unit = \"cd\", "
                        "radius = 0.1 }"),
              "bad.lua:1: scene.light.a.unit: a sphere light cannot be given in 'cd' (seed 000 "
              "tbl:8); expected 'lm', 'nits', 'ev100'");
    EXPECT_EQ(
        lua.error("scene.light \"a\" { type = \"point\", intensity = 100, unit = \"lumen\" }"),
        "bad.lua:1: scene.light.a.unit: unknown unit 'lumen'; a point light takes 'lm', 'cd'");
    EXPECT_EQ(lua.error("scene.light \"a\" { type = \"pointt\", intensity = 1 }"),
              "bad.lua:1: scene.light.a.type: unknown light type 'pointt' (did you mean 'point'?); "
              "expected one of: 'point', 'spot', "
              "'sun', 'directional', 'sphere', 'disk', 'rect', 'tube'");
    EXPECT_EQ(lua.error("scene.light \"a\" { intensity = 1 }"),
              "bad.lua:1: scene.light.a.type: missing (expected one of: 'point', 'spot', 'sun', "
              "'sphere', 'disk', 'rect', 'tube')");
    EXPECT_EQ(lua.error("scene.light \"a\" { type = \"point\" }"),
              "bad.lua:1: scene.light.a.intensity: missing (expected a number, in 'lm', 'cd')");
    EXPECT_EQ(lua.error("scene.light \"a\" { type = \"point\", intensity = -5 }"),
              "bad.lua:1: scene.light.a.intensity: expected a number >= 0, got -5");
    EXPECT_EQ(lua.error("scene.light \"a\" { type = \"point\", intensity = 5, color = { 1, 1, 1 }, "
                        "temperature = 3000 }"),
              "bad.lua:1: scene.light.a.temperature: give either color or temperature, not both");
    EXPECT_EQ(
        lua.error("scene.light \"a\" { type = \"point\", intensity = 5, temperature = 1000 }"),
        "bad.lua:1: scene.light.a.temperature: expected a number in [1667, 25000], got 1000");
    EXPECT_EQ(lua.error("scene.light \"a\" { type = \"point\", intensity = 5, temperature = 3000, "
                        "locus = \"daylight\" }"),
              "bad.lua:1: scene.light.a.temperature: expected a number in [4000, 25000], got 3000");
    EXPECT_EQ(
        lua.error("scene.light \"a\" { type = \"point\", intensity = 5, locus = \"daylight\" }"),
        "bad.lua:1: scene.light.a.locus: applies with a temperature only");
    EXPECT_EQ(lua.error("scene.light \"a\" { type = \"disk\", intensity = 5, radius = 0.1, "
                        "direction = { 0, -1, 0 }, inner_angle = 10 }"),
              "bad.lua:1: scene.light.a.inner_angle: a disk's cone needs its outer_angle too (seed "
              "000 lst:9)");
    EXPECT_EQ(lua.error("scene.light \"a\" { type = \"point\", intensity = 5, width = 1 }"),
              "bad.lua:1: scene.light.a.width: not used by a point light (only by rect lights)");
    EXPECT_EQ(lua.error("scene.light \"s\" { type = \"sun\", intensity = 5, direction = { 0, -1, 0 "
                        "}, range = 3 }"),
              "bad.lua:1: scene.light.s.range: not used by a sun light (only by local lights)");
    EXPECT_EQ(lua.error("scene.light \"s\" { type = \"sun\", intensity = 5, direction = { 0, -1, 0 "
                        "}, shadow = true }"),
              "bad.lua:1: scene.light.s.shadow: not used by a sun light (only by local lights; the "
              "sun's shadow is the pipeline's sun_shadows parameter)");
    EXPECT_EQ(lua.error("scene.light \"a\" { type = \"point\", intensity = 5, shadow = 1 }"),
              "bad.lua:1: scene.light.a.shadow: expected a boolean, got 1");
    EXPECT_EQ(
        lua.error("scene.light \"a\" { type = \"spot\", intensity = 5 }"),
        "bad.lua:1: scene.light.a.direction: missing (a spot light needs direction or target)");
    EXPECT_EQ(lua.error("scene.light \"a\" { type = \"spot\", intensity = 5, direction = { 0, -1, "
                        "0 }, inner_angle = 40, outer_angle = 30 }"),
              "bad.lua:1: scene.light.a.inner_angle: is 40°, wider than outer_angle (30°)");
    EXPECT_EQ(lua.error("scene.light \"a\" { type = \"rect\", intensity = 5, direction = { 0, -1, "
                        "0 }, width = 1 }"),
              "bad.lua:1: scene.light.a.height: missing (a rect light needs its height in metres)");
    EXPECT_EQ(lua.error("scene.light \"a\" { type = \"tube\", intensity = 5, unit = \"ev100\", "
                        "direction = { 1, 0, 0 }, radius = 0.02 }"),
              "bad.lua:1: scene.light.a.length: missing (a tube light needs its length in metres)");
    EXPECT_EQ(lua.error("scene.light \"a\" { type = \"point\", intensity = 5, ies = \"x.ies\" }"),
              "bad.lua:1: scene.light.a.ies: cannot open '" + lua.dir +
                  "/x.ies': No such file or directory");
    EXPECT_EQ(
        lua.error("scene.light \"a\" { type = \"point\", intensity = 5, exact_cone = true }"),
        "bad.lua:1: scene.light.a.exact_cone: not used by a point light (only by spot lights)");
    EXPECT_EQ(
        lua.error("scene.light \"a\" { type = \"point\", intensity = 5, ies_mode = \"mask\" }"),
        "bad.lua:1: scene.light.a.ies_mode: needs an ies profile to apply");
    EXPECT_EQ(lua.error("scene.light \"a\" { type = \"sphere\", intensity = 5, radius = 1, "
                        "ies_mode = \"mask\" }"),
              "bad.lua:1: scene.light.a.ies_mode: not used by a sphere light (only by point and "
              "spot lights with an IES profile)");
    // Valid: EV100 may be negative; spot angles are degrees, stored in radians.
    auto ok = lua.run("ok.lua",
                      "scene.light \"a\" { type = \"disk\", intensity = -2, unit = \"ev100\", "
                      "radius = 0.5, target = { 0, 0, 0 }, position = { 0, 2, 0 } }\n"
                      "scene.light \"b\" { type = \"spot\", intensity = 800, direction = { 0, -1, "
                      "0 }, inner_angle = 20, outer_angle = 30,\n"
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
    EXPECT_EQ(lua.error("scene.camera \"c\" { fov = 200 }"),
              "bad.lua:1: scene.camera.c.fov: expected a number in (0, 180), got 200");
    EXPECT_EQ(lua.error("scene.camera \"c\" { fov = 40, focal_length = 50 }"),
              "bad.lua:1: scene.camera.c.focal_length: give either fov or focal_length (with "
              "sensor_height), not both");
    EXPECT_EQ(lua.error("scene.camera \"c\" { position = { 0, 0, 0 }, target = { 0, 0, 0 } }"),
              "bad.lua:1: scene.camera.c.target: equals position; the camera needs a direction to "
              "look in");
    EXPECT_EQ(lua.error("scene.camera \"c\" { near = 10, far = 5 }"),
              "bad.lua:1: scene.camera.c.far: is 5, not beyond near (10)");
    EXPECT_EQ(lua.error("scene.camera \"c\" { position = { 0, 10, 0 } }"),
              "bad.lua:1: scene.camera.c.up: is parallel to the view direction (or zero); e.g. up "
              "= {0, 0, -1} for a camera looking straight down");
    EXPECT_EQ(lua.error("scene.camera \"c\" { aperture = 0 }"),
              "bad.lua:1: scene.camera.c.aperture: expected a number in [0.5, 128], got 0");
    EXPECT_EQ(lua.error("scene.camera \"c\" { height = 4, fov = 30 }"),
              "bad.lua:1: scene.camera.c.height: an orthographic camera (height) has no fov or "
              "focal_length");
    EXPECT_EQ(lua.error("scene.camera \"c\" { height = 0 }"),
              "bad.lua:1: scene.camera.c.height: expected a number > 0, got 0");
    EXPECT_EQ(lua.error("scene.environment \"e\" { kind = \"hdri\" }"),
              "bad.lua:1: scene.environment.e.kind: unknown environment kind 'hdri' (did you mean "
              "'hdr'?); expected one of: 'sky', "
              "'hdr', 'color'");
    EXPECT_EQ(lua.error("scene.environment \"e\" { kind = \"hdr\", file = \"sky.hdr\" }"),
              "bad.lua:1: scene.environment.e.file: cannot open '" + lua.dir +
                  "/sky.hdr': No such file or directory");
    EXPECT_EQ(lua.error("scene.environment \"e\" { kind = \"sky\", unit = \"lux\" }"),
              "bad.lua:1: scene.environment.e.unit: an environment's luminance is in 'nits' (seed "
              "000 tbl:8), got 'lux'");
    EXPECT_EQ(lua.error("scene.environment \"e\" { kind = \"sky\", sun = \"keep\" }"),
              "bad.lua:1: scene.environment.e.sun: applies to kind = \"hdr\" only (a sky's sun is "
              "the scene's light)");
    EXPECT_EQ(lua.error("scene.environment \"z\" { kind = \"sky\" }\nscene.environment \"b\" { "
                        "kind = \"sky\" }"),
              "bad.lua:2: scene.environment.b: a scene has one environment; 'z' is declared at "
              "bad.lua:1");
    // A Lua error and a missing script pass through with their position.
    EXPECT_EQ(lua.error("scene.sphere \"a\" {").rfind("bad.lua:1:", 0), 0u);
    auto missing = rg::loadSceneScript(lua.dir + "/none.lua");
    ASSERT_FALSE(missing);
    EXPECT_EQ(missing.error().code, ErrorCode::NotFound);
    EXPECT_EQ(missing.error().message,
              "scene script: cannot open '" + lua.dir + "/none.lua': No such file or directory");

    // Focal length and sensor height in millimetres give the vertical field of view.
    auto ok = lua.run("cam.lua",
                      "scene.camera \"c\" { focal_length = 50, sensor_height = 24, aperture = 2.8, "
                      "shutter = 0.01, iso = 400, ec = -1 }");
    ASSERT_TRUE(ok) << errorOf(ok);
    EXPECT_NEAR(ok->cameras[0].verticalFov, 2 * std::atan(12.0f / 50.0f), 1e-6f);
    EXPECT_FLOAT_EQ(ok->cameras[0].focalLength, 0.05f);
    EXPECT_FLOAT_EQ(ok->cameras[0].iso, 400.0f);
    EXPECT_FLOAT_EQ(ok->cameras[0].exposureCompensation, -1.0f);
}

TEST(SceneScript, ProbesAndTheirFieldErrors) {
    ScriptRunner lua("probes");
    // The README's example (scripts/scenes/README.md).
    auto ok = lua.run("probes.lua",
                      "scene.probe \"room\" { shape = \"box\", position = { 0, 1.5, 0 }, size = { "
                      "8, 3, 6 }, fade = 0.5 }\n"
                      "scene.probe \"alcove\" { position = { 3, 1, -2 }, radius = 1.5, influence = "
                      "2.5, priority = 1 }");
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
    auto wide = lua.run(
        "wide.lua",
        "scene.probe \"s\" { radius = 1, influence = 3 }\n"
        "scene.probe \"b\" { shape = \"box\", size = { 1, 2, 3 }, influence = { 4, 5, 6 } }");
    ASSERT_TRUE(wide) << errorOf(wide);
    EXPECT_FLOAT_EQ(wide->probes[0].influenceRadius, 3.0f);
    EXPECT_EQ(wide->probes[1].influenceSize, glm::vec3(4, 5, 6));
    EXPECT_EQ(lua.error("scene.probe \"p\" { influence = 0 }"),
              "bad.lua:1: scene.probe.p.influence: expected a number > 0, got 0");
    EXPECT_EQ(lua.error("scene.probe \"p\" { size = { 1, 1, 1 } }"),
              "bad.lua:1: scene.probe.p.size: a sphere probe has a radius (give shape = \"box\" "
              "for a size)");
    EXPECT_EQ(lua.error("scene.probe \"p\" { shape = \"box\", radius = 2 }"),
              "bad.lua:1: scene.probe.p.radius: a box probe has a size, not a radius");
    EXPECT_EQ(lua.error("scene.probe \"p\" { shape = \"cone\" }"),
              "bad.lua:1: scene.probe.p.shape: unknown probe shape 'cone'; expected one of: "
              "'sphere', 'box'");
    EXPECT_EQ(
        lua.error("scene.probe \"p\" { priority = 1.5 }"),
        "bad.lua:1: scene.probe.p.priority: expected a whole number in [-1000, 1000], got 1.5");
    EXPECT_EQ(lua.error("scene.probe \"p\" { radius = 0 }"),
              "bad.lua:1: scene.probe.p.radius: expected a number > 0, got 0");
    EXPECT_EQ(lua.error("for i = 1, 9 do scene.probe(\"p\" .. i) {} end"),
              "bad.lua:1: scene.probe.p9: a scene has at most 8 light probes "
              "(shaders/lib/probes.glsl RG_MAX_PROBES)");
}

TEST(SceneScript, DefaultCameraFramesTheBounds) {
    ScriptRunner lua("defcam");
    auto scene =
        lua.run("s.lua", "scene.box \"b\" { size = { 2, 2, 2 }, position = { 10, 1, 0 } }");
    ASSERT_TRUE(scene) << errorOf(scene);
    ASSERT_EQ(scene->cameras.size(), 1u);
    const rg::Camera& c = scene->cameras[0];
    EXPECT_EQ(c.name, "default");
    expectNear(c.target, {10, 1, 0}, 1e-5f, "looks at the centre");
    // Every corner of the bounds is inside the vertical field of view.
    const glm::vec3 fwd = glm::normalize(c.target - c.position);
    for (int k = 0; k < 8; ++k) {
        const glm::vec3 p((k & 1) ? scene->boundsMax.x : scene->boundsMin.x,
                          (k & 2) ? scene->boundsMax.y : scene->boundsMin.y,
                          (k & 4) ? scene->boundsMax.z : scene->boundsMin.z);
        EXPECT_GT(glm::dot(glm::normalize(p - c.position), fwd), std::cos(c.verticalFov / 2)) << k;
    }
    // Objects without a material share a grey default one.
    EXPECT_EQ(scene->materials.size(), 1u);
    EXPECT_EQ(scene->materials[0].name, "default");
}

TEST(SceneScript, ObjectsMoveAlongTheirPaths) {
    ScriptRunner lua("paths");
    auto scene =
        lua.run("s.lua",
                "scene.box \"b\" { position = { 1, 2, 3 }, rotation = { 0, 0, 90 }, "
                "scale = 2, path = {\n"
                "  { time = 0, rotation = { 0, 0, 0 } }, { time = 1, position = { 2, 2, 3 } },\n"
                "  { time = 2, position = { 3, 2, 3 }, rotation = { 0, 0, 180 } },\n"
                "  { time = 3, position = { 4, 2, 3 }, rotation = { 0, 0, 270 } } } }\n"
                "scene.sphere \"s\" {}");
    ASSERT_TRUE(scene) << errorOf(scene);
    ASSERT_EQ(scene->nodes.size(), 2u);
    const rg::Node& box = scene->nodes[0];
    EXPECT_TRUE(box.dynamic);
    EXPECT_FALSE(scene->nodes[1].dynamic);
    EXPECT_EQ(scene->nodes[1].at(5.0), scene->nodes[1].world);  // no path: where it stands
    // A key without position or rotation keeps the declaration's; the first frame is at t = 0.
    expectNear(origin(box.world), {1, 2, 3}, 1e-6f, "at load");
    expectNear(glm::vec3(box.world[0]), {2, 0, 0}, 1e-6f, "at load: the first key's rotation");
    expectNear(origin(box.at(0.0)), {1, 2, 3}, 1e-6f, "first key");
    // Between evenly spaced keys on a line, Catmull-Rom tangents are the constant speed: exactly
    // linear from t = 1 to 2 (1 m/s), eased into the first key's rest before.
    expectNear(origin(box.at(1.25)), {2.25f, 2, 3}, 1e-5f, "middle segment");
    expectNear(origin(box.at(1.75)), {2.75f, 2, 3}, 1e-5f, "middle segment");
    EXPECT_LT(origin(box.at(0.25)).x, 1.25f);  // eased out of the first key
    expectNear(origin(box.at(9.0)), {4, 2, 3}, 1e-6f, "held after the last key");
    // Rotation about Z at 90°/s (keys every 90°), the scale kept: the box's +x axis turns from +y
    // (90°, the declaration's own rotation at key 1) through 135° at t = 1.5 (twice its length:
    // scale 2).
    const glm::vec3 axis = glm::vec3(box.at(1.5)[0]);
    expectNear(axis, {-std::sqrt(2.0f), std::sqrt(2.0f), 0}, 1e-5f, "turned 135°, scaled 2");
    // Errors name the key and field.
    EXPECT_EQ(lua.error("scene.box \"b\" { path = { { time = 0 } } }"),
              "bad.lua:1: scene.box.b.path: expected a list of at least two keys { time = s, "
              "position = {x, y, z}, rotation = {x, y, z} in degrees }, got {a table}");
    EXPECT_EQ(lua.error("scene.box \"b\" { path = { { time = 1 }, { time = 1 } } }"),
              "bad.lua:1: scene.box.b.path[2].time: is 1, not after the key before (1)");
    EXPECT_EQ(lua.error("scene.box \"b\" { path = { { time = 0 }, { position = { 1, 2, 3 } } } }"),
              "bad.lua:1: scene.box.b.path[2]: a key needs a time");
    EXPECT_EQ(lua.error("scene.box \"b\" { path = { { time = 0 }, { time = 1, scale = 2 } } }"),
              "bad.lua:1: scene.box.b.path[2].scale: unknown field; expected one of: 'time', "
              "'position', 'rotation'");
}

// A glTF file's animation plays under the declaration's placement, and under its path when it
// has one; `animation = "none"` keeps the file still.
TEST(SceneScript, AGltfAnimationPlaysUnderItsPlacementAndPath) {
    ScriptRunner lua("gltf_animation");
    GltfBuilder g;
    addQuad(g, true);
    const int q = g.node({{"name", "q"}, {"mesh", 0}});
    g.scene({q});
    const int times = g.floats({0, 1}, "SCALAR"), slide = g.floats({0, 0, 0, 1, 0, 0}, "VEC3");
    g.j["animations"] = json::array(
        {{{"samplers", {{{"input", times}, {"output", slide}}}},
          {"channels", {{{"sampler", 0}, {"target", {{"node", q}, {"path", "translation"}}}}}}}});
    fs::create_directories(lua.dir + "/models");
    g.writeGltf(lua.dir + "/models", "slide");
    auto scene =
        lua.run("s.lua",
                "scene.gltf \"placed\" { file = \"models/slide.gltf\", position = { 10, 0, 0 }, "
                "scale = 2 }\n"
                "scene.gltf \"still\" { file = \"models/slide.gltf\", animation = \"none\" }\n"
                "scene.gltf \"moved\" { file = \"models/slide.gltf\", position = { 0, 0, 1 }, "
                "rotation = { 0, 90, 0 }, scale = 2, path = { { time = 0 }, "
                "{ time = 1, position = { 0, 0, 5 } } } }");
    ASSERT_TRUE(scene) << errorOf(scene);
    ASSERT_EQ(scene->nodes.size(), 3u);
    // 1 m along x over a second, scaled 2 by the placement: 1 m at 0.5 s.
    EXPECT_TRUE(scene->nodes[0].dynamic);
    expectNear(origin(scene->nodes[0].at(0.5)), {11, 0, 0}, 1e-5f, "placed");
    EXPECT_FALSE(scene->nodes[1].dynamic);
    // The path (two keys from the declaration's position: eased, half way at 0.5 s, keeping its
    // 90° about y) with the declaration's scale 2 and the animation below it: the slide's 0.5 m
    // along x, doubled, turned to −z.
    expectNear(origin(scene->nodes[2].at(0.5)), {0, 0, 3.0f - 1.0f}, 1e-5f, "under a path");
}

TEST(SceneScript, GltfIsMergedWithItsTransform) {
    ScriptRunner lua("merge");
    GltfBuilder g;
    addQuad(g, true);
    g.j["materials"] =
        json::array({{{"name", "paint"}, {"pbrMetallicRoughness", {{"roughnessFactor", 0.25}}}}});
    g.j["meshes"][0]["primitives"][0]["material"] = 0;
    g.j["extensions"]["KHR_lights_punctual"]["lights"] =
        json::array({{{"type", "point"}, {"intensity", 2.0}}});
    g.scene({g.node({{"name", "q"}, {"mesh", 0}, {"translation", {0, 1, 0}}}),
             g.node({{"name", "l"},
                     {"translation", {1, 0, 0}},
                     {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}})});
    fs::create_directories(lua.dir + "/models");
    g.writeGltf(lua.dir + "/models", "thing");
    auto scene = lua.run("s.lua",
                         "scene.material \"m\" {}\nscene.sphere \"s\" { material = \"m\" }\n"
                         "scene.gltf \"thing\" { file = \"models/thing.gltf\", position = { 10, 0, "
                         "0 }, rotation = { 0, 90, 0 }, scale = 2 }");
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
    expectNear(scene->lights[0].position, {10, 0, -2}, 1e-5f,
               "light moved, turned and scaled with the model");
    EXPECT_EQ(scene->files.size(), 3u);  // the script, the .gltf and its .bin
}

}  // namespace

// What the GPU light tests (tests/gpu/test_lights*.cpp) share: the Lights fixture, which renders a
// scene with the default pipeline and reads back absolute luminance, the camera's view of the
// floor, and the CPU twins of the lights (graph/lighting).
#pragma once

#include <gtest/gtest.h>

#include "gpu_fixture.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <utility>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "runtime/runtime.h"
#include "runtime/session.h"
#include "core/light_units.h"
#include "image/image.h"
#include "layout/layout.h"
#include "lighting/area_lights.h"
#include "lighting/brdf.h"
#include "lighting/ies.h"
#include "lighting/punctual.h"
#include "passes/gpu_scene.h"

namespace rg::test {

inline const std::string kRoot = RG_SOURCE_ROOT;
inline const std::string kScenes = kRoot + "/tests/gpu/scenes/";
// Odd, so the centre pixel's centre is exactly on the camera's axis.
inline constexpr uint32_t W = 129, H = 129;
inline constexpr double kPi = 3.14159265358979323846;

inline const glm::dvec3 kUp{0.0, 1.0, 0.0};

inline std::string readFile(const std::string& path) {
    std::ifstream in(path);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// The scene file with its scene.light line (one line) replaced and other replacements made,
// written next to the other test outputs. Paths in the new line must be absolute.
inline std::string withLight(const std::string& file, const std::string& light,
                             const std::string& name,
                             const std::vector<std::pair<std::string, std::string>>& replace = {}) {
    std::string text = readFile(kScenes + file);
    const size_t at = text.find("\nscene.light");
    EXPECT_NE(at, std::string::npos) << file;
    const size_t end = std::min(text.find('\n', at + 1), text.size());
    text.replace(at + 1, end - at - 1, light);
    for (const auto& [from, to] : replace) {
        const size_t i = text.find(from);
        EXPECT_NE(i, std::string::npos) << from;
        if (i != std::string::npos) text.replace(i, from.size(), to);
    }
    const std::string out = std::string(RG_TEST_TMP) + "/" + name + ".lua";
    std::ofstream(out) << text;
    return out;
}

// ---- The camera as GpuScene::updateFrame sets it -------------------------------------------------

struct View {
    glm::dmat4 viewProj{1.0}, invViewProj{1.0};
    glm::dvec3 eye{0.0};
};

inline View viewOf(const Camera& c) {
    const float fovy = c.focalLength > 0 ? 2.0f * std::atan(c.sensorHeight / (2.0f * c.focalLength))
                                         : c.verticalFov;
    glm::mat4 proj = glm::perspectiveRH_ZO(fovy, float(W) / float(H), c.nearPlane, c.farPlane);
    proj[1][1] *= -1.0f;
    View v;
    v.viewProj = glm::dmat4(proj * glm::lookAt(c.position, c.target, c.up));
    v.invViewProj = glm::inverse(v.viewProj);
    v.eye = glm::dvec3(c.position);
    return v;
}

inline glm::ivec2 pixelOf(const View& v, glm::dvec3 p) {
    const glm::dvec4 clip = v.viewProj * glm::dvec4(p, 1.0);
    const glm::dvec2 ndc = glm::dvec2(clip) / clip.w;
    return glm::ivec2(glm::floor((ndc * 0.5 + 0.5) * glm::dvec2(W, H)));
}

// Where the centre of pixel px meets the floor (y = 0): the position the lighting pass shades.
inline glm::dvec3 floorAt(const View& v, glm::ivec2 px) {
    const glm::dvec2 ndc = (glm::dvec2(px) + 0.5) / glm::dvec2(W, H) * 2.0 - 1.0;
    glm::dvec4 a = v.invViewProj * glm::dvec4(ndc, 0.0, 1.0),
               b = v.invViewProj * glm::dvec4(ndc, 1.0, 1.0);
    const glm::dvec3 p0 = glm::dvec3(a) / a.w, p1 = glm::dvec3(b) / b.w;
    const double t = p0.y / (p0.y - p1.y);
    return p0 + t * (p1 - p0);
}

// ---- The CPU side: BRDF halves (graph/lighting/brdf.h) and the lights' illuminance ---------------

inline glm::vec3 fv(glm::dvec3 v) { return glm::vec3(v); }

// The diffuse BRDF without ⟨n·l⟩ (Fr_DisneyDiffuse / π), as lighting.glsl's rgDiffuseBrdf.
inline double diffuseBrdf(glm::dvec3 N, glm::dvec3 V, glm::dvec3 L, float linearRoughness) {
    const glm::dvec3 Hv = glm::normalize(V + L);
    const float NdotV = float(std::abs(glm::dot(N, V))) + 1e-5f;
    const float NdotL = float(std::clamp(glm::dot(N, L), 0.0, 1.0));
    const float LdotH = float(std::clamp(glm::dot(L, Hv), 0.0, 1.0));
    return brdf::Fr_DisneyDiffuse(NdotV, NdotL, LdotH, linearRoughness) / brdf::kPi;
}
// The specular BRDF with ⟨n·l⟩ (rgStandardBrdf with a black diffuse colour).
inline double specularBrdf(glm::dvec3 N, glm::dvec3 V, glm::dvec3 L, float f0,
                           float linearRoughness) {
    return brdf::rgStandardBrdf(fv(N), fv(V), fv(L), glm::vec3(0.0f), glm::vec3(f0),
                                linearRoughness)
        .x;
}

inline double areaLuminance(const Light& l) {
    lighting::AreaLightShape shape;
    shape.shape = l.type == LightType::Sphere ? lighting::AreaShape::Sphere
                  : l.type == LightType::Disk ? lighting::AreaShape::Disk
                  : l.type == LightType::Tube ? lighting::AreaShape::Tube
                                              : lighting::AreaShape::Rectangle;
    shape.radius = l.radius;
    shape.length = l.length;
    shape.width = l.width;
    shape.height = l.height;
    const auto unit = l.unit == "lm"     ? lighting::AreaUnit::Lumens
                      : l.unit == "nits" ? lighting::AreaUnit::Nits
                                         : lighting::AreaUnit::Ev100;
    return lighting::areaLightLuminance(shape, l.intensity, unit);
}

// A rect's axes as convertLights makes them: up perpendicular to the direction, left = up × n.
inline void rectAxes(const Light& l, glm::dvec3& n, glm::dvec3& up, glm::dvec3& left) {
    n = glm::normalize(glm::dvec3(l.direction));
    up = glm::normalize(glm::dvec3(l.up) - glm::dot(glm::dvec3(l.up), n) * n);
    left = glm::cross(up, n);
}

struct Expected {
    double diffuseIlluminance = 0;  // lux, cosine and horizon included
    glm::dvec3 Ld{0.0};             // the direction the diffuse lobe sees the light from
};

// graph/lighting's illuminance of an area light at floor point P (normal N).
inline Expected areaIlluminance(const Light& l, glm::dvec3 P, glm::dvec3 N) {
    const double Lum = areaLuminance(l);
    const glm::dvec3 pos(l.position), dir = glm::normalize(glm::dvec3(l.direction));
    const glm::dvec3 Lu = pos - P;
    const double sqrDist = glm::dot(Lu, Lu);
    const glm::dvec3 L = Lu / std::sqrt(sqrDist);
    Expected e;
    e.Ld = L;
    switch (l.type) {
        case LightType::Sphere:
            e.diffuseIlluminance =
                Lum * lighting::sphereIlluminance(l.radius, sqrDist, glm::dot(N, L));
            break;
        case LightType::Disk:
            e.diffuseIlluminance = Lum * lighting::diskIlluminance(
                                             l.radius, sqrDist, glm::dot(N, L), glm::dot(dir, -L));
            break;
        case LightType::Rect: {
            glm::dvec3 n, up, left;
            rectAxes(l, n, up, left);
            e.diffuseIlluminance =
                Lum * lighting::rectangleIlluminance(P, N, pos, left, up, n, l.width, l.height);
            break;
        }
        case LightType::Tube: {
            const glm::dvec3 p0 = pos - dir * (0.5 * l.length), p1 = pos + dir * (0.5 * l.length);
            e.diffuseIlluminance = Lum * lighting::tubeIlluminance(P, N, p0, p1, l.radius);
            const double t =
                std::clamp(glm::dot(P - p0, p1 - p0) / glm::dot(p1 - p0, p1 - p0), 0.0, 1.0);
            e.Ld = glm::normalize(p0 + t * (p1 - p0) - P);
            break;
        }
        default:
            ADD_FAILURE() << "not an area light";
    }
    return e;
}

// ---- The fixture --------------------------------------------------------------------------------

// The floor as the lighting pass reads it from the G-buffer (decoded with the layout's C++ unpack):
// +y through 10+10-bit octahedral encoding is 1e-3 rad off, which a glossy lobe notices.
struct Surface {
    glm::dvec3 normal = kUp;
    double baseColor = 1.0;
    float linearRoughness = 1.0f;
    float f0 = 0.0f;
};

struct Frame {
    Image hdr;  // absolute luminance (cd/m²): the HDR divided by its pre-exposure
    Scene scene;
    View view;
    Surface floor;             // at the centre pixel
    bool finite = true;        // every HDR and display value
    bool lightTexels = false;  // the light loops read the lights through a texel buffer
};

class Lights : public GpuFixture {
protected:
    // Renders `scene` with the default pipeline at manual exposure (the scene camera's settings)
    // and no sky (every image holds the light's contribution only), two frames, and reads back
    // the HDR in cd/m² and the floor's surface at the centre pixel.
    static Frame render(const std::string& scene) {
        SessionOptions o;
        o.compile.outputWidth = W;
        o.compile.outputHeight = H;
        o.scene = scene;
        o.captures = {"GB0", "GB1", "GB2", "GB3"};
        o.params["light_shapes"] = Value(false);  // the light's lighting alone, not its look
        o.paramsIfDeclared["taa_jitter"] = Value(false);   // pixels compared one by one
        o.paramsIfDeclared["specular_aa"] = Value(false);  // roughness as the scene gives it
        Session s(*s_runtime, o);
        Frame out;
        auto r = s.load(kRoot + "/scripts/pipelines/deferred.lua");
        EXPECT_TRUE(r.has_value()) << r.error().describe();
        if (!r) return out;
        auto& p = const_cast<PipelineDesc&>(s.pipeline());
        p.findParam("exposure_mode")->value = Value("manual");
        // The CPU twins here are Frostbite's approximations (graph/lighting/area_lights.h); the LTC
        // model is judged against the reference by test_accuracy.
        p.findParam("area_lights")->value = Value("frostbite");
        s_runtime->executor().updateUniforms(graphWithParams(p));
        for (int f = 0; f < 2; ++f) {
            auto fr = s.frame();
            EXPECT_TRUE(fr.has_value()) << fr.error().describe();
        }
        auto hdr = s_runtime->executor().readback("hdr");
        auto display = s_runtime->executor().readback("display");
        auto state = s_runtime->executor().readbackBuffer("exposure");
        EXPECT_TRUE(hdr.has_value() && display.has_value() && state.has_value());
        if (!hdr || !display || !state) return out;
        float st[4];
        std::memcpy(st, state->data(), sizeof st);
        const float pre = st[2];  // the pre-exposure this frame's HDR was rendered with
        EXPECT_GT(pre, 0.0f);
        for (float v : hdr->pixels) out.finite = out.finite && std::isfinite(v);
        for (float v : display->pixels) out.finite = out.finite && std::isfinite(v);
        for (float& v : hdr->pixels) v /= pre;
        out.hdr = std::move(*hdr);
        out.scene = *s.scene();
        out.view = viewOf(out.scene.cameras.front());
        out.lightTexels = s.gpuScene()->lightTexelView(0) != VK_NULL_HANDLE;

        auto info = analyzeLayout(s.pipeline().layouts.front());
        EXPECT_TRUE(info.has_value());
        if (!info) return out;
        std::vector<TexelValue> texels;
        const size_t centre = size_t(H / 2) * W + W / 2;
        for (const auto& t : info->desc.targets) {
            auto img = s_runtime->executor().readback(t.name);
            EXPECT_TRUE(img.has_value()) << t.name;
            if (!img) return out;
            texels.push_back(
                texelFromFloats(t.format, &img->pixels[centre * img->channels], img->channels));
        }
        const auto g = unpackTexel(*info, texels);
        auto ch = [&](const char* n) { return g[static_cast<size_t>(info->find(n))].v; };
        out.floor.normal =
            glm::normalize(glm::dvec3(ch("normal")[0], ch("normal")[1], ch("normal")[2]));
        out.floor.baseColor = ch("baseColor")[1];
        out.floor.linearRoughness = 1.0f - ch("smoothness")[0];
        out.floor.f0 = brdf::rgDielectricF0(ch("reflectance")[0]);
        EXPECT_EQ(ch("metalMask")[0], 0.0f);
        EXPECT_GT(glm::dot(out.floor.normal, kUp), 0.999999);
        return out;
    }

public:
    static double luminanceAt(const Frame& f, glm::ivec2 px) {
        return f.hdr.at(uint32_t(px.x), uint32_t(px.y),
                        1);  // the floors are white/grey: any channel
    }
    // Leaves the image to look at when a comparison fails.
    static void keep(const Frame& f, const std::string& name) {
        const std::string path = std::string(RG_TEST_TMP) + "/lights_" + name + ".exr";
        ImageLayer layer;
        layer.name = "hdr";
        layer.channelNames = {"R", "G", "B", "A"};
        layer.image = f.hdr;
        (void)writeExr(path, {layer}, {ExrPixelType::Float});
        std::printf("  (image: %s)\n", path.c_str());
    }

protected:
};

}  // namespace rg::test

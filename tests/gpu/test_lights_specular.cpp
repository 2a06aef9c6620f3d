// Area lights on the GPU beyond the diffuse floor: the forward pass's rgLightIlluminance, and the
// specular lobe at the representative point (seed 002 §4.7.5) as the lights shrink and grow.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "lights_fixture.h"

using namespace rg;
using namespace rg::test;

namespace {

// ---- The forward pass: rgLightIlluminance ---------------------------------------------------------

TEST_F(Lights, ForwardPassLightsBlendedSurfacesByAreaLights) {
    // The generated forward shader (passes/scene_pass.cpp) calls rgLightIlluminance(i, P, L): for
    // an area light, its illuminance on a surface facing it, towards its centre. A white, purely
    // diffuse pane (opacity 0.5) 0.3 m above the floor, under a sphere light; the pane's own
    // luminance is what the blend adds: (P(0.5) − 0.5 P(0)) / 0.5.
    auto frame = [&](const char* opacity, const char* light) {
        return render(withLight(
            "lights_area.lua", light, "forward",
            {{"scene.camera", std::string("scene.material \"pane\" { base_color = { 1, 1, 1 }, "
                                          "smoothness = 0, reflectance = 0, "
                                          "alpha = \"blend\", opacity = ") +
                                  opacity +
                                  " }\nscene.box \"pane\" { size = { 1, 0.02, 1 }, position = { 0, "
                                  "0.3, 0 }, material = \"pane\" }\nscene.camera"}}));
    };
    const char* sphere =
        "scene.light \"area\" { type = \"sphere\", intensity = 2000, unit = \"lm\", radius = 0.2, "
        "position = { 0, 1.2, 0 } }";
    Frame blended = frame("0.5", sphere), clear = frame("0", sphere);
    ASSERT_TRUE(blended.finite && clear.finite);
    const glm::ivec2 centre(W / 2, H / 2);
    const double pane = (luminanceAt(blended, centre) - 0.5 * luminanceAt(clear, centre)) / 0.5;
    const Light& l = blended.scene.lights.front();
    const glm::dvec3 P{0.0, 0.31, 0.0}, Lu = glm::dvec3(l.position) - P;
    const double sqrDist = glm::dot(Lu, Lu);
    // lst:10 at the clamped cos θ = 0.999 of a surface facing the centre, times the diffuse BRDF.
    const double E = areaLuminance(l) * lighting::sphereIlluminance(l.radius, sqrDist, 1.0);
    const glm::dvec3 L = glm::normalize(Lu), V = glm::normalize(blended.view.eye - P);
    const double want =
        E * brdf::rgStandardBrdf(fv(kUp), fv(V), fv(L), glm::vec3(1.0f), glm::vec3(0.0f), 1.0f).x;
    std::printf(
        "forward pane under a sphere light: E %.3f lx, CPU %.4f cd/m², GPU %.4f cd/m² (%+.3f %%)\n",
        E, want, pane, 100.0 * (pane - want) / want);
    EXPECT_NEAR(pane, want, 0.01 * want);
    // Every other area light reaches the forward pass too: the pane is lit and finite.
    for (const char* light : {
             "scene.light \"area\" { type = \"disk\", intensity = 2000, unit = \"lm\", radius = "
             "0.2, position = { 0, 1.2, 0 }, direction = { 0, -1, 0 } }",
             "scene.light \"area\" { type = \"rect\", intensity = 2000, unit = \"lm\", width = "
             "0.4, height = 0.3, position = { 0, 1.2, 0 }, direction = { 0, -1, 0 }, up = { 0, 0, "
             "1 } }",
             "scene.light \"area\" { type = \"tube\", intensity = 2000, unit = \"lm\", radius = "
             "0.02, length = 0.6, position = { 0, 1.2, 0 }, direction = { 1, 0, 0 } }",
         }) {
        Frame b = frame("0.5", light), c = frame("0", light);
        ASSERT_TRUE(b.finite && c.finite) << light;
        const double lum = (luminanceAt(b, centre) - 0.5 * luminanceAt(c, centre)) / 0.5;
        EXPECT_GT(lum, 0.1 * want) << light;
        EXPECT_LT(lum, 10.0 * want) << light;
    }
}

// ---- Specular: the representative point (seed 002 §4.7.5) ----------------------------------------

// lighting.glsl's specular sample, in double: the representative direction, the illuminance
// facing it and the widening normalisation.
struct Specular {
    glm::dvec3 Ls{0.0};
    double E = 0, norm = 1;
};
double widening(double alpha, double angle) {
    return alpha / std::clamp(alpha + 0.5 * std::clamp(angle, 0.0, 1.0), 0.0, 1.0);
}
glm::dvec3 rayOnPlane(glm::dvec3 centre, glm::dvec3 n, glm::dvec3 R) {
    const double denom = glm::dot(R, n);
    const double t = denom < -1e-4 ? glm::dot(centre, n) / denom : -1.0;
    const glm::dvec3 hit = t > 0 ? R * t : glm::dot(centre, R) * R;
    return hit - glm::dot(hit - centre, n) * n;
}
Specular specularSample(const Light& l, glm::dvec3 P, glm::dvec3 N, glm::dvec3 V, double alpha) {
    const double Lum = areaLuminance(l);
    const glm::dvec3 R = lighting::getSpecularDominantDirArea(N, glm::reflect(-V, N), alpha);
    const glm::dvec3 Lu = glm::dvec3(l.position) - P, dir = glm::normalize(glm::dvec3(l.direction));
    const double sqrDist = glm::dot(Lu, Lu), dist = std::sqrt(sqrDist), r = l.radius;
    Specular s;
    if (l.type == LightType::Sphere) {
        const glm::dvec3 c = glm::dot(Lu, R) * R - Lu;
        s.Ls = glm::normalize(Lu + c * std::clamp(r / glm::length(c), 0.0, 1.0));
        s.E = Lum * kPi * std::min(r * r / sqrDist, 0.9999);
        s.norm = std::pow(widening(alpha, r / dist), 2);
    } else if (l.type == LightType::Disk) {
        const glm::dvec3 o = rayOnPlane(Lu, dir, R) - Lu;
        s.Ls = glm::normalize(Lu + o * std::min(1.0, r / glm::length(o)));
        s.E = Lum * kPi * r * r / (r * r + std::max(r * r, sqrDist)) *
              std::clamp(glm::dot(dir, -Lu / dist), 0.0, 1.0);
        s.norm = std::pow(widening(alpha, r / dist), 2);
    } else if (l.type == LightType::Rect) {
        glm::dvec3 n, up, left;
        rectAxes(l, n, up, left);
        const double hw = 0.5 * l.width, hh = 0.5 * l.height;
        const glm::dvec3 o = rayOnPlane(Lu, n, R) - Lu;
        s.Ls = glm::normalize(Lu + left * std::clamp(glm::dot(o, left), -hw, hw) +
                              up * std::clamp(glm::dot(o, up), -hh, hh));
        s.E = Lum * lighting::rectangleSolidAngle(
                        P, P + Lu - left * hw + up * hh, P + Lu - left * hw - up * hh,
                        P + Lu + left * hw - up * hh, P + Lu + left * hw + up * hh);
        s.norm = widening(alpha, hw / dist) * widening(alpha, hh / dist);
    } else {  // tube
        const glm::dvec3 L0 = Lu - dir * (0.5 * l.length), ab = dir * double(l.length);
        const double t = std::clamp((glm::dot(R, L0) * glm::dot(R, ab) - glm::dot(L0, ab)) /
                                        (glm::dot(ab, ab) - std::pow(glm::dot(R, ab), 2)),
                                    0.0, 1.0);
        const glm::dvec3 onSegment = L0 + ab * t;
        const glm::dvec3 c = glm::dot(onSegment, R) * R - onSegment;
        s.Ls = glm::normalize(onSegment + c * std::clamp(r / glm::length(c), 0.0, 1.0));
        // The facing rectangle of the capsule and the sphere at the segment's closest point.
        const double tc = std::clamp(glm::dot(-L0, ab) / glm::dot(ab, ab), 0.0, 1.0);
        const double tl = glm::dot(-L0, ab) / glm::dot(ab, ab);
        const glm::dvec3 closest = L0 + tc * ab, forward = glm::normalize(L0 + tl * ab),
                         upv = glm::cross(dir, forward);
        const double hl = 0.5 * l.length;
        const double omega = lighting::rectangleSolidAngle(
            P, P + Lu - dir * hl + r * upv, P + Lu - dir * hl - r * upv,
            P + Lu + dir * hl - r * upv, P + Lu + dir * hl + r * upv);
        s.E = Lum * (omega + kPi * std::min(r * r / glm::dot(closest, closest), 1.0));
        s.norm = std::pow(widening(alpha, r / dist), 2) * widening(alpha, l.length / dist);
    }
    return s;
}

TEST_F(Lights, SpecularLobeLooksAtTheRepresentativePoint) {
    // A glossy floor (smoothness 0.7, reflectance 0.5) seen at an angle, each area light in front:
    // diffuse as above plus GGX towards the representative point × its normalisation.
    const char* lights[] = {
        "scene.light \"area\" { type = \"sphere\", intensity = 2000, unit = \"lm\", radius = 0.25, "
        "position = { 0, 1, -1 } }",
        "scene.light \"area\" { type = \"disk\", intensity = 2000, unit = \"lm\", radius = 0.3, "
        "position = { 0, 1, -1 }, direction = { 0, -0.6, 0.8 } }",
        "scene.light \"area\" { type = \"rect\", intensity = 2000, unit = \"lm\", width = 0.8, "
        "height = 0.4, position = { 0, 1, -1 }, direction = { 0, -0.6, 0.8 }, up = { 0, 1, 0 } }",
        "scene.light \"area\" { type = \"tube\", intensity = 2000, unit = \"lm\", radius = 0.04, "
        "length = 1.0, position = { 0, 1, -1 }, direction = { 1, 0, 0 } }",
    };
    for (const char* text : lights) {
        Frame f = render(withLight("lights_glossy.lua", text, "glossy"));
        ASSERT_TRUE(f.finite);
        const Light& l = f.scene.lights.front();
        const double alpha =
            std::max(double(f.floor.linearRoughness) * f.floor.linearRoughness, 1e-3);
        // The mirror point of the light's centre seen from the camera (the highlight), and around.
        const glm::dvec3 eye = f.view.eye, c(l.position);
        const double tm = eye.y / (eye.y + c.y);
        const glm::dvec3 mirror = eye + tm * (glm::dvec3(c.x, -c.y, c.z) - eye);
        double peak = 0;
        bool failed = false;
        for (glm::dvec3 target :
             {mirror, mirror + glm::dvec3(0.15, 0, 0.1), mirror + glm::dvec3(-0.3, 0, 0.4),
              glm::dvec3(0.8, 0, 0.5), glm::dvec3(-1.0, 0, -0.3)}) {
            const glm::ivec2 px = pixelOf(f.view, target);
            const glm::dvec3 P = floorAt(f.view, px);
            const glm::dvec3 V = glm::normalize(eye - P);
            const Surface& fl = f.floor;
            const Expected d = areaIlluminance(l, P, fl.normal);
            const Specular s = specularSample(l, P, fl.normal, V, alpha);
            const double diffuse = fl.baseColor *
                                   diffuseBrdf(fl.normal, V, d.Ld, fl.linearRoughness) *
                                   d.diffuseIlluminance;
            const double specular =
                specularBrdf(fl.normal, V, s.Ls, fl.f0, fl.linearRoughness) * s.E * s.norm;
            const double want = diffuse + specular;
            const double got = luminanceAt(f, px);
            peak = std::max(peak, specular / want);
            std::printf(
                "%-6s spec at (%6.3f, %6.3f): diffuse %9.4f + specular %9.4f (norm %.3f) = CPU "
                "%9.4f, GPU %9.4f cd/m² (%+.3f %%)\n",
                lightTypeName(l.type), P.x, P.z, diffuse, specular, s.norm, want, got,
                100.0 * (got - want) / want);
            EXPECT_NEAR(got, want, 0.01 * want)
                << lightTypeName(l.type) << " at " << P.x << ", " << P.z;
            failed = failed || std::abs(got - want) > 0.01 * want;
        }
        EXPECT_GT(peak, 0.5) << "the highlight should dominate at the mirror point";
        if (failed) keep(f, std::string("spec_") + lightTypeName(l.type));
    }
}

TEST_F(Lights, TinySphereLightsLikeThePointLight) {
    // eq:38: a sphere in lumens lights like the point light of the same lumens; as its radius goes
    // to zero its representative point is its centre and the normalisation 1, so the whole image —
    // diffuse and the glossy floor's highlight — converges to the point light's.
    Frame point = render(withLight("lights_glossy.lua",
                                   "scene.light \"area\" { type = \"point\", intensity = 2000, "
                                   "unit = \"lm\", position = { 0, 1, -1 } }",
                                   "tiny_point"));
    Frame sphere = render(withLight("lights_glossy.lua",
                                    "scene.light \"area\" { type = \"sphere\", intensity = 2000, "
                                    "unit = \"lm\", radius = 0.0001, position = { 0, 1, -1 } }",
                                    "tiny_sphere"));
    double worst = 0, sumPoint = 0, sumSphere = 0;
    for (size_t i = 0; i < point.hdr.pixels.size(); i += 4) {
        const double a = point.hdr.pixels[i + 1], b = sphere.hdr.pixels[i + 1];
        sumPoint += a;
        sumSphere += b;
        if (a > 1.0) worst = std::max(worst, std::abs(b - a) / a);
    }
    std::printf("0.1 mm sphere vs point light: worst pixel %.3f %%, image sum %+.4f %%\n",
                100 * worst, 100 * (sumSphere - sumPoint) / sumPoint);
    EXPECT_LT(worst, 0.01);
    EXPECT_NEAR(sumSphere, sumPoint, 0.002 * sumPoint);
}

TEST_F(Lights, LumensHighlightsDimAsTheLightGrows) {
    // seed 000 §4.7.1, Figure 31, on a smoother floor (smoothness 0.95, a lobe narrower than the
    // lights): in lumens, a larger sphere spreads the same power — the floor's
    // overall level stays, the highlight gets wider and dimmer; in nits, the highlight keeps its
    // brightness and the scene gets brighter.
    auto frame = [&](double radius, const char* unit, double value, const char* name) {
        char text[200];
        std::snprintf(text, sizeof text,
                      "scene.light \"area\" { type = \"sphere\", intensity = %g, unit = \"%s\", "
                      "radius = %g, position = { 0, 1, -1 } }",
                      value, unit, radius);
        return render(withLight("lights_glossy.lua", text, name,
                                {{"smoothness = 0.7", "smoothness = 0.95"}}));
    };
    auto stats = [](const Frame& f, double& peak, double& sum) {
        peak = sum = 0;
        for (size_t i = 1; i < f.hdr.pixels.size(); i += 4) {
            peak = std::max(peak, double(f.hdr.pixels[i]));
            sum += f.hdr.pixels[i];
        }
    };
    double peakSmall, sumSmall, peakLarge, sumLarge, peakNitsSmall, sumNitsSmall, peakNitsLarge,
        sumNitsLarge;
    stats(frame(0.1, "lm", 2000, "grow_small"), peakSmall, sumSmall);
    stats(frame(0.4, "lm", 2000, "grow_large"), peakLarge, sumLarge);
    stats(frame(0.1, "nits", 10000, "grow_nits_small"), peakNitsSmall, sumNitsSmall);
    stats(frame(0.4, "nits", 10000, "grow_nits_large"), peakNitsLarge, sumNitsLarge);
    std::printf(
        "lm:   peak %.1f -> %.1f, sum %.0f -> %.0f\nnits: peak %.1f -> %.1f, sum %.0f -> %.0f\n",
        peakSmall, peakLarge, sumSmall, sumLarge, peakNitsSmall, peakNitsLarge, sumNitsSmall,
        sumNitsLarge);
    EXPECT_LT(peakLarge, 0.5 * peakSmall);
    EXPECT_NEAR(sumLarge, sumSmall, 0.1 * sumSmall);
    EXPECT_GT(sumNitsLarge, 8.0 * sumNitsSmall);  // 16× the area
    EXPECT_GT(peakNitsLarge, 0.5 * peakNitsSmall);
}

}  // namespace

// Lights on the GPU against their CPU twins (graph/lighting): the default deferred pipeline renders
// a floor of known material under one light (tests/gpu/scenes/lights_*.lua), with manual exposure,
// and the HDR divided by its pre-exposure is absolute luminance. At pixels whose floor position is
// computed from the camera, luminance = the CPU's illuminance × the CPU's BRDF within 1 %:
// point (seed 000 tbl:10), sphere (lst:10, across the horizon), disk, rectangle and tube (seed 002
// §4.7.2.5–6), the sun (lst:6, 100 000 lux, no NaN or inf) and the units (lm, nits, EV100: one
// image). IES, specular and tiled lights: test_lights_ies.cpp, _specular.cpp, _tiles.cpp.
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

// Compares a frame lit by one area light with graph/lighting at floor points (white, diffuse only).
void checkAreaLight(const Frame& f, const std::vector<glm::dvec3>& points, const char* what,
                    double* worst = nullptr) {
    ASSERT_EQ(f.scene.lights.size(), 1u);
    const Light& l = f.scene.lights.front();
    bool failed = false;
    for (const glm::dvec3& target : points) {
        const glm::ivec2 px = pixelOf(f.view, target);
        const glm::dvec3 P = floorAt(f.view, px);
        const glm::dvec3 V = glm::normalize(f.view.eye - P);
        const glm::dvec3 N = f.floor.normal;
        const Expected e = areaIlluminance(l, P, N);
        const double want = f.floor.baseColor * diffuseBrdf(N, V, e.Ld, f.floor.linearRoughness) *
                            e.diffuseIlluminance;
        const double got = Lights::luminanceAt(f, px);
        std::printf(
            "%-6s at (%6.3f, %6.3f): E %10.4f lx, CPU %10.4f cd/m², GPU %10.4f cd/m² (%+.3f %%)\n",
            what, P.x, P.z, e.diffuseIlluminance, want, got,
            want > 0 ? 100.0 * (got - want) / want : 0.0);
        EXPECT_NEAR(got, want, 0.01 * want + 1e-4) << what << " at " << P.x << ", " << P.z;
        if (worst && want > 0) *worst = std::max(*worst, std::abs(got - want) / want);
        failed = failed || std::abs(got - want) > 0.01 * want + 1e-4;
    }
    if (failed) Lights::keep(f, what);
}

// ---- Point light: seed 000 tbl:10 ----------------------------------------------------------------

TEST_F(Lights, PointLightGivesTable10) {
    // 625 lm at 1, 0.5, 0.25, 0.1 m above a white floor: E = Φ / (4π d²) below it (eq:19), and the
    // luminance there is E times the standard BRDF at normal incidence (Disney diffuse at linear
    // roughness 1 is 1/1.51/π, not Lambert's 1/π, plus a 4 % specular lobe at α = 1).
    const double heights[] = {1.0, 0.5, 0.25, 0.1};
    const double table[] = {49.7, 198.9, 795.8, 4973.6};
    for (int i = 0; i < 4; ++i) {
        char light[160];
        std::snprintf(light, sizeof light,
                      "scene.light \"bulb\" { type = \"point\", intensity = 625, unit = \"lm\", "
                      "position = { 0, %g, 0 } }",
                      heights[i]);
        Frame f = render(withLight("lights_point.lua", light, "point"));
        const glm::ivec2 centre(W / 2, H / 2);
        const glm::dvec3 P = floorAt(f.view, centre);
        ASSERT_NEAR(glm::length(P), 0.0, 1e-5);  // the centre pixel is right below the light
        const double E = lights::illuminance(lights::pointIntensityFromLumens(625.0), heights[i]);
        EXPECT_NEAR(E, table[i], 0.05);
        const glm::dvec3 V = glm::normalize(f.view.eye - P);
        const glm::dvec3 L = glm::normalize(glm::dvec3(0, heights[i], 0) - P);
        const Surface& s = f.floor;
        const double brdfWithCosine =
            brdf::rgStandardBrdf(fv(s.normal), fv(V), fv(L), glm::vec3(float(s.baseColor)),
                                 glm::vec3(s.f0), s.linearRoughness)
                .x;
        const double want = E * brdfWithCosine;
        const double got = luminanceAt(f, centre);
        std::printf(
            "point  625 lm at %.2f m: E %.1f lx (tbl:10 %.1f), BRDF·cos %.5f, CPU %.3f cd/m², GPU "
            "%.3f cd/m² (%+.3f %%)\n",
            heights[i], E, table[i], brdfWithCosine, want, got, 100.0 * (got - want) / want);
        EXPECT_NEAR(got, want, 0.01 * want) << heights[i] << " m";
        // And off-axis, 0.4 m aside: E = I cos θ / d².
        const glm::ivec2 aside = pixelOf(f.view, {0.4, 0.0, 0.0});
        const glm::dvec3 Q = floorAt(f.view, aside);
        const glm::dvec3 toLight = glm::dvec3(0, heights[i], 0) - Q;
        const glm::dvec3 Lq = glm::normalize(toLight);
        const double Eq =
            lights::illuminance(lights::pointIntensityFromLumens(625.0), glm::length(toLight), 1.0);
        const double wantQ =
            Eq * brdf::rgStandardBrdf(fv(s.normal), fv(glm::normalize(f.view.eye - Q)), fv(Lq),
                                      glm::vec3(float(s.baseColor)), glm::vec3(s.f0),
                                      s.linearRoughness)
                     .x;
        EXPECT_NEAR(luminanceAt(f, aside), wantQ, 0.01 * wantQ) << heights[i] << " m, 0.4 m aside";
    }
    // Disney diffuse at normal incidence and linear roughness 1: lightScatter = viewScatter = 1, so
    // the renormalisation factor alone, 1/1.51 (lst:1).
    EXPECT_NEAR(brdf::Fr_DisneyDiffuse(1.0f, 1.0f, 1.0f, 1.0f), 1.0 / 1.51, 1e-6);
}

// ---- Area lights (diffuse): graph/lighting --------------------------------------------------------

TEST_F(Lights, SphereLightMatchesListing10AcrossTheHorizon) {
    // lights_area.lua: a 0.5 m sphere whose centre is 0.4 m above the floor. Right below it the floor
    // is inside the sphere: nothing reaches it (the surface emits outwards); 1.5 m aside it
    // straddles the horizon (cos θ 0.26 < sin σ 0.32).
    Frame f = render(kScenes + "lights_area.lua");
    ASSERT_TRUE(f.finite);
    const Light& l = f.scene.lights.front();
    {  // the horizon really is crossed at the far point
        const glm::dvec3 P{1.5, 0.0, 0.0}, Lu = glm::dvec3(l.position) - P;
        ASSERT_LT(glm::dot(glm::normalize(Lu), kUp), l.radius / glm::length(Lu));
    }
    checkAreaLight(f,
                   {{0.0, 0, 0.0},
                    {0.6, 0, 0.2},
                    {0.9, 0, -0.4},
                    {1.5, 0, 0.0},
                    {-1.1, 0, 1.2},
                    {2.2, 0, 0.5}},
                   "sphere");
}

TEST_F(Lights, DiskLightMatchesListing10) {
    // Facing down 1 m up, then tilted, then facing sideways close to the floor (half of it below
    // the horizon of the points in front).
    const char* disks[] = {
        "scene.light \"area\" { type = \"disk\", intensity = 1500, unit = \"lm\", radius = 0.3, "
        "position = { 0, 1, 0 }, direction = { 0, -1, 0 } }",
        "scene.light \"area\" { type = \"disk\", intensity = 1500, unit = \"lm\", radius = 0.4, "
        "position = { 0, 0.8, 0 }, direction = { 0.6, -0.8, 0 } }",
        "scene.light \"area\" { type = \"disk\", intensity = 20000, unit = \"nits\", radius = 0.5, "
        "position = { -0.5, 0.2, 0 }, direction = { 1, 0, 0 } }",
    };
    for (const char* d : disks) {
        Frame f = render(withLight("lights_area.lua", d, "disk"));
        ASSERT_TRUE(f.finite);
        checkAreaLight(
            f, {{0.0, 0, 0.0}, {0.7, 0, 0.3}, {-0.9, 0, -0.5}, {1.6, 0, 0.1}, {0.4, 0, -1.5}},
            "disk");
    }
}

TEST_F(Lights, DiskConeAttenuatesLikeASpotFromItsApex) {
    // seed 000 lst:9: a disk 1 m up facing down with a cone (inner 20°, outer 35°): each floor point
    // gets the cone-less disk's light × getAngleAtt seen from the apex r / tan(35°) behind the disk —
    // all of it under the disk, none beyond the outer cone, the smooth edge between.
    const std::string base =
        "scene.light \"area\" { type = \"disk\", intensity = 1500, unit = \"lm\", radius = 0.3, "
        "position = { 0, 1, 0 }, "
        "direction = { 0, -1, 0 }";
    Frame plain = render(withLight("lights_area.lua", base + " }", "disk_plain"));
    Frame coned = render(
        withLight("lights_area.lua", base + ", inner_angle = 20, outer_angle = 35 }", "disk_cone"));
    ASSERT_TRUE(plain.finite && coned.finite);
    ASSERT_TRUE(coned.scene.lights.front().cone);
    const auto cone =
        lighting::spotAngleScaleOffset(20.0f * float(kPi) / 180.0f, 35.0f * float(kPi) / 180.0f);
    const glm::dvec3 apex =
        lighting::diskVirtualPosition({0, 1, 0}, {0, -1, 0}, 0.3, 35.0 * kPi / 180.0);
    int inside = 0, outside = 0, edge = 0;
    for (double x : {0.0, 0.2, 0.45, 0.6, 0.75, 0.9, 1.2}) {
        const glm::ivec2 px = pixelOf(plain.view, {x, 0.0, 0.1});
        const glm::dvec3 P = floorAt(plain.view, px);
        const double att = lighting::getAngleAtt(glm::vec3(-glm::normalize(apex - P)),
                                                 glm::vec3(0, -1, 0), cone.scale, cone.offset);
        const double want = luminanceAt(plain, px) * att, got = luminanceAt(coned, px);
        std::printf(
            "disk cone at x = %.2f: attenuation %.3f, cone-less %.4f, expected %.4f, got %.4f "
            "cd/m²\n",
            P.x, att, luminanceAt(plain, px), want, got);
        EXPECT_NEAR(got, want, 0.01 * luminanceAt(plain, px) + 1e-5) << P.x;
        (att > 0.999 ? inside : att < 1e-4 ? outside : edge) += 1;
    }
    EXPECT_GE(inside, 1);
    EXPECT_GE(outside, 1);
    EXPECT_GE(edge, 1);
}

TEST_F(Lights, RectangleLightMatchesStructuredSampling) {
    const char* rects[] = {
        "scene.light \"area\" { type = \"rect\", intensity = 3000, unit = \"lm\", width = 1.0, "
        "height = 0.5, position = { 0, 1, 0 }, direction = { 0, -1, 0 }, up = { 0, 0, 1 } }",
        // Standing on the floor, facing +x: points behind it get nothing, points in front see its
        // lower half near their horizon.
        "scene.light \"area\" { type = \"rect\", intensity = 5000, unit = \"nits\", width = 1.2, "
        "height = 0.8, position = { 0, 0.3, 0 }, direction = { 1, 0, 0 }, up = { 0, 1, 0 } }",
    };
    for (const char* r : rects) {
        Frame f = render(withLight("lights_area.lua", r, "rect"));
        ASSERT_TRUE(f.finite);
        checkAreaLight(
            f, {{0.1, 0, 0.05}, {0.8, 0, 0.3}, {-0.9, 0, -0.5}, {1.6, 0, 0.9}, {0.3, 0, -1.4}},
            "rect");
    }
}

TEST_F(Lights, TubeLightMatchesCapsuleApproximation) {
    const char* tubes[] = {
        "scene.light \"area\" { type = \"tube\", intensity = 2500, unit = \"lm\", radius = 0.05, "
        "length = 1.2, position = { 0, 0.6, 0 }, direction = { 1, 0, 0 } }",
        "scene.light \"area\" { type = \"tube\", intensity = 8, unit = \"ev100\", radius = 0.1, "
        "length = 0.8, position = { 0.2, 0.5, -0.3 }, direction = { 0, 0.6, 0.8 } }",
    };
    for (const char* t : tubes) {
        Frame f = render(withLight("lights_area.lua", t, "tube"));
        ASSERT_TRUE(f.finite);
        checkAreaLight(
            f, {{0.0, 0, 0.0}, {0.5, 0, 0.3}, {0.9, 0, -0.2}, {-1.1, 0, 0.6}, {0.2, 0, 1.3}},
            "tube");
    }
}

TEST_F(Lights, AreaLightUnitsGiveOneImage) {
    // One sphere light declared in lm, in nits (tbl:12: Φ / (4 r² π²)) and in EV100 (eq:12:
    // L = 2^(EV − 3)): the same luminance, the same image (half precision: within 1e-3).
    const double lumens = 2000.0, radius = 0.5;
    const double nits = lighting::sphereLuminanceFromLumens(lumens, radius);
    const double ev100 = std::log2(nits) + 3.0;
    char a[200], b[200], c[200];
    std::snprintf(a, sizeof a,
                  "scene.light \"area\" { type = \"sphere\", intensity = %.17g, unit = \"lm\", "
                  "radius = 0.5, position = { 0, 0.4, 0 } }",
                  lumens);
    std::snprintf(b, sizeof b,
                  "scene.light \"area\" { type = \"sphere\", intensity = %.17g, unit = \"nits\", "
                  "radius = 0.5, position = { 0, 0.4, 0 } }",
                  nits);
    std::snprintf(c, sizeof c,
                  "scene.light \"area\" { type = \"sphere\", intensity = %.17g, unit = \"ev100\", "
                  "radius = 0.5, position = { 0, 0.4, 0 } }",
                  ev100);
    Frame fl = render(withLight("lights_area.lua", a, "unit_lm"));
    Frame fn = render(withLight("lights_area.lua", b, "unit_nits"));
    Frame fe = render(withLight("lights_area.lua", c, "unit_ev100"));
    double worstNits = 0, worstEv = 0, lit = 0;
    for (size_t i = 0; i < fl.hdr.pixels.size(); ++i) {
        const double ref = fl.hdr.pixels[i];
        if (ref <= 0) continue;
        lit += 1;
        worstNits = std::max(worstNits, std::abs(fn.hdr.pixels[i] - ref) / ref);
        worstEv = std::max(worstEv, std::abs(fe.hdr.pixels[i] - ref) / ref);
    }
    std::printf(
        "units: %.4f cd/m² = %.4f EV100; worst relative difference nits %.2e, ev100 %.2e over %.0f "
        "values\n",
        nits, ev100, worstNits, worstEv, lit);
    EXPECT_GT(lit, double(W) * H);  // the floor is lit everywhere
    EXPECT_LT(worstNits, 1e-3);
    EXPECT_LT(worstEv, 1e-3);
}

// ---- The sun: seed 000 lst:6, eq:28 -------------------------------------------------------------

TEST_F(Lights, SunOf100000LuxIsFiniteAndLightsByEq28) {
    Frame f = render(kScenes + "lights_sun.lua");
    EXPECT_TRUE(f.finite) << "NaN or inf in the HDR or display image";
    const Light& sun = f.scene.lights.front();
    const glm::dvec3 D = -glm::normalize(glm::dvec3(sun.direction));
    // The white floor away from the ball (and its shadow-free lighting): luminance = E⊥ ⟨n·D⟩ Fd(D)
    // + the specular lobe at lst:6's closest point of the sun's disk (α = 1: the dominant direction
    // is the normal; the widening normalisation is 1).
    for (glm::dvec3 target : {glm::dvec3{-1.0, 0, -1.0}, glm::dvec3{0.0, 0, 0.0},
                              glm::dvec3{-1.5, 0, 1.2}, glm::dvec3{0.3, 0, -1.6}}) {
        const glm::ivec2 px = pixelOf(f.view, target);
        const glm::dvec3 P = floorAt(f.view, px);
        const glm::dvec3 V = glm::normalize(f.view.eye - P);
        const glm::dvec3 N = f.floor.normal;
        const double E = lighting::sunIlluminance(100000.0, glm::dot(N, D));
        const glm::dvec3 R = lighting::getSpecularDominantDirArea(N, glm::reflect(-V, N), 1.0);
        const glm::dvec3 Ls = lighting::sunSpecularDirection(D, R, sun.sunAngularRadius);
        const double want =
            diffuseBrdf(N, V, D, 1.0f) * E + specularBrdf(N, V, Ls, f.floor.f0, 1.0f) * 100000.0;
        const double got = luminanceAt(f, px);
        std::printf(
            "sun    at (%6.3f, %6.3f): E %.1f lx, CPU %.2f cd/m², GPU %.2f cd/m² (%+.3f %%)\n", P.x,
            P.z, E, want, got, 100.0 * (got - want) / want);
        EXPECT_NEAR(got, want, 0.01 * want);
    }
    // The ball is lit and its highlight is finite and bright: the sun reflected in a smooth metal.
    float peak = 0;
    for (float v : f.hdr.pixels) peak = std::max(peak, v);
    EXPECT_GT(peak, 1e5f);
}

}  // namespace

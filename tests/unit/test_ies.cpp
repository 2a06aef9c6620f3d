// IES profiles on the CPU (seed 000 §4.5, lst:5): LM-63 1986 to 2019, types A, B and C, broken
// files with their exact messages, symmetry, evaluation, lumens and the baked texture. No GPU.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "lighting/ies.h"
#include "lighting/punctual.h"
#include "lighting_test_util.h"

using namespace rg;
using namespace rg::test;

namespace {

// ---- IES helpers ----------------------------------------------------------------------------

std::string iesPath(const std::string& name) {
    return std::string(RG_SOURCE_ROOT) + "/tests/unit/ies/" + name;
}

IesProfile loadOrFail(const std::string& name) {
    auto p = loadIes(iesPath(name));
    EXPECT_TRUE(p.has_value()) << (p ? "" : p.error().describe());
    return p ? *p : IesProfile{};
}

std::string parseError(const std::string& text, const std::string& name = "lamp.ies") {
    auto p = parseIes(text, name);
    if (p) return "(parsed without error)";
    return p.error().message;
}

ErrorCode parseErrorCode(const std::string& text) {
    auto p = parseIes(text, "lamp.ies");
    return p ? ErrorCode::CheckFailed : p.error().code;
}

}  // namespace

// =============================================================================================
// IES profiles (seed 000 §4.5)
// =============================================================================================

TEST(Ies, ParsesLm63_2002) {
    const IesProfile p = loadOrFail("downlight_2002.ies");
    EXPECT_EQ(p.format, IesFormat::Lm63_2002);
    ASSERT_EQ(p.keywords.size(), 8u);  // [MORE] joins [LUMINAIRE]
    EXPECT_EQ(p.keywords[0].name, "TEST");
    EXPECT_EQ(p.keywords[0].value, "RG-0001 (hand-written for rgraph's unit tests)");
    EXPECT_EQ(p.keywords[5].name, "LUMINAIRE");
    EXPECT_EQ(p.keywords[5].value,
              "Recessed downlight, 150 mm aperture, clear reflector\nwide distribution, 2700 K");
    EXPECT_EQ(p.keywords[6].name, "LAMP");
    EXPECT_EQ(p.numberOfLamps, 1);
    EXPECT_EQ(p.lumens, 1800.0f);
    EXPECT_EQ(p.multiplier, 1.0f);
    EXPECT_EQ(p.photometricType, 1);
    EXPECT_EQ(p.unitsType, 2);
    EXPECT_FLOAT_EQ(p.width, 0.15f);
    EXPECT_EQ(p.inputWatts, 18.0f);
    ASSERT_EQ(p.verticalAngles.size(), 19u);
    EXPECT_EQ(p.verticalAngles.back(), 90.0f);
    ASSERT_EQ(p.horizontalAngles.size(), 1u);
    EXPECT_EQ(p.symmetry, IesSymmetry::Rotational);
    ASSERT_EQ(p.candela.size(), 19u);
    EXPECT_EQ(p.candela[0], 850.0f);
    EXPECT_EQ(p.candela[10], 321.5f);
    EXPECT_EQ(p.maxCandela, 850.0f);
    // The distribution's flux (1671 lm by an independent integration of the table) is below the
    // lamp's 1800 lm: a luminaire absorbs some of its lamp's light.
    const double flux = integrateLumens(p);
    EXPECT_NEAR(flux, 1671.4, 2.0);
    EXPECT_LT(flux, static_cast<double>(p.lumens) * p.numberOfLamps);
}

TEST(Ies, ParsesLm63_1995Quadrant) {
    const IesProfile p = loadOrFail("wallwash_1995.ies");
    EXPECT_EQ(p.format, IesFormat::Lm63_1995);
    EXPECT_EQ(p.numberOfLamps, 2);
    EXPECT_EQ(p.lumens, 1350.0f);
    EXPECT_FLOAT_EQ(p.ballastFactor, 0.95f);
    EXPECT_EQ(p.symmetry, IesSymmetry::Quadrant);
    ASSERT_EQ(p.verticalAngles.size(), 9u);
    ASSERT_EQ(p.horizontalAngles.size(), 5u);
    EXPECT_EQ(p.horizontalAngles[1], 22.5f);
    ASSERT_EQ(p.candela.size(), 45u);
    EXPECT_EQ(p.candela[1 * 9 + 0], 911.5f);  // [h = 22.5][v = 0]
    EXPECT_EQ(p.candela[4 * 9 + 8], 5.0f);    // [h = 90][v = 180]
    EXPECT_EQ(p.maxCandela, 1024.0f);
}

TEST(Ies, ParsesLm63_1991Bilateral) {
    const IesProfile p = loadOrFail("bilateral_1991.ies");
    EXPECT_EQ(p.format, IesFormat::Lm63_1991);
    EXPECT_EQ(p.keywords.size(), 3u);
    EXPECT_EQ(p.symmetry, IesSymmetry::Bilateral);
    EXPECT_EQ(p.horizontalAngles.back(), 180.0f);
    EXPECT_EQ(p.candela.size(), 20u);
    EXPECT_EQ(p.maxCandela, 470.0f);
}

TEST(Ies, ParsesLm63_1986WithCommasAndValuesSplitAcrossLines) {
    const IesProfile p = loadOrFail("street_1986.ies");
    EXPECT_EQ(p.format, IesFormat::Lm63_1986);
    ASSERT_EQ(p.keywords.size(), 2u);  // the two label lines
    EXPECT_EQ(p.keywords[0].name, "");
    EXPECT_EQ(p.keywords[0].value, "STREET LIGHT TYPE II, ROADWAY");
    EXPECT_EQ(p.lumens, 4000.0f);
    EXPECT_EQ(p.multiplier, 2.0f);
    EXPECT_EQ(p.unitsType, 1);  // feet
    EXPECT_EQ(p.inputWatts, 150.0f);
    EXPECT_EQ(p.verticalAngles, (std::vector<float>{0, 15, 30, 45, 60, 75, 90}));
    EXPECT_EQ(p.horizontalAngles, (std::vector<float>{0, 90, 180, 270, 360}));
    EXPECT_EQ(p.symmetry, IesSymmetry::None);
    ASSERT_EQ(p.candela.size(), 35u);
    // The multiplier is applied: 325 in the file is 650 cd.
    EXPECT_EQ(p.candela[0], 650.0f);
    EXPECT_EQ(p.candela[1 * 7 + 0], 550.0f);  // h = 90: 275 × 2
    EXPECT_EQ(p.candela[3 * 7 + 0], 450.0f);  // h = 270: 225 × 2
    EXPECT_EQ(p.maxCandela, 650.0f);
}

TEST(Ies, ParsesAbsolutePhotometryWithCrLfAndThe90To270Range) {
    const IesProfile p = loadOrFail("pendant_2002.ies");
    EXPECT_EQ(p.format, IesFormat::Lm63_2002);
    EXPECT_EQ(p.lumens, -1.0f);                                     // absolute photometry
    EXPECT_EQ(p.keywords[0].value, "RG-0005 absolute photometry");  // no '\r' left over
    EXPECT_EQ(p.symmetry, IesSymmetry::Bilateral90);
    EXPECT_EQ(p.horizontalAngles.front(), 90.0f);
    EXPECT_EQ(p.verticalAngles.back(), 180.0f);
    EXPECT_EQ(p.candela.size(), 25u);
}

namespace {

// A small valid LM-63-2002 file; the error tests break one thing each. Line numbers:
// 1 format, 2–3 keywords, 4 TILT, 5 lamp values, 6 ballast values, 7 vertical angles,
// 8 horizontal angles, 9–10 candela.
std::string validIes() {
    return "IESNA:LM-63-2002\n"
           "[TEST] ERR\n"
           "[MANUFAC] rgraph\n"
           "TILT=NONE\n"
           "1 1000 1 5 2 1 2 0 0 0\n"
           "1 1 10\n"
           "0 22.5 45 67.5 90\n"
           "0 90\n"
           "100 90 70 40 0\n"
           "100 80 60 30 0\n";
}

std::string replaceLine(std::string text, int line, const std::string& with) {
    size_t start = 0;
    for (int i = 1; i < line; ++i) start = text.find('\n', start) + 1;
    const size_t end = text.find('\n', start);
    return text.replace(start, end - start, with);
}

}  // namespace

TEST(Ies, ValidBaseFileParses) { EXPECT_EQ(parseError(validIes()), "(parsed without error)"); }

TEST(Ies, ErrorWrongNumberOfVerticalAngles) {
    // The example: 37 announced, 20 on the vertical angle lines (line 12), then the horizontal
    // angles start.
    std::string text =
        "IESNA:LM-63-2002\n[TEST] T\n[TESTLAB] L\n[ISSUEDATE] 2024\n[MANUFAC] M\n[LUMCAT] C\n"
        "[LUMINAIRE] X\n[LAMP] Y\nTILT=NONE\n1 1000 1 37 2 1 2 0 0 0\n1 1 10\n";
    for (int i = 0; i < 20; ++i) text += std::to_string(i * 5) + (i == 9 ? "\n" : " ");
    text += "\n0 90\n";
    // The data is a consistent 20 x 2 table, only the header's count is wrong …
    std::string consistent = text;
    for (int h = 0; h < 2; ++h) {
        for (int v = 0; v < 20; ++v) consistent += "100 ";
        consistent += "\n";
    }
    EXPECT_EQ(parseError(consistent), "'lamp.ies':12: expected 37 vertical angles, found 20");
    // … or the candela lines have 37 values: found where the horizontal angles start over at 0.
    for (int h = 0; h < 2; ++h) {
        for (int v = 0; v < 37; ++v) text += "100 ";
        text += "\n";
    }
    EXPECT_EQ(parseError(text), "'lamp.ies':12: expected 37 vertical angles, found 20");
    // One value too many on the line: the block runs on.
    EXPECT_EQ(parseError(replaceLine(validIes(), 7, "0 22.5 45 67.5 90 95")),
              "'lamp.ies':7: expected 5 vertical angles, found 6");
    // Too few horizontal angles: the candela values start early.
    EXPECT_EQ(
        parseError(replaceLine(replaceLine(validIes(), 5, "1 1000 1 5 3 1 2 0 0 0"), 8, "0 90")),
        "'lamp.ies':8: expected 3 horizontal angles, found 2");
}

TEST(Ies, ErrorMissingTilt) {
    EXPECT_EQ(parseError(replaceLine(validIes(), 4, "[MORE] no tilt here")),
              "'lamp.ies':5: missing TILT line: expected 'TILT=NONE' before the photometric data, "
              "found '1 1000 1 5 2 1 2 0 0 0'");
    EXPECT_EQ(parseError("IESNA:LM-63-2002\n[TEST] nothing else\n"),
              "'lamp.ies':2: missing TILT line: expected 'TILT=NONE' before the photometric data, "
              "found the end of the file");
    EXPECT_EQ(parseErrorCode(replaceLine(validIes(), 4, "[MORE] x")), ErrorCode::InvalidInput);
}

TEST(Ies, TiltIncludeAndTiltFileAreReadAndKept) {
    // LM-63-2002 §3.10: TILT=INCLUDE puts the tilt block (geometry, count, angles, factors) between
    // the TILT line and the lamp line; the photometry after it reads as usual.
    const std::string included =
        replaceLine(validIes(), 4, "TILT=INCLUDE\n1\n3\n0 45 90\n1.0 0.95 0.9");
    auto p = parseIes(included, "lamp.ies");
    ASSERT_TRUE(p.has_value()) << p.error().message;
    EXPECT_EQ(p->tilt, "INCLUDE");
    EXPECT_EQ(p->tiltGeometry, 1);
    EXPECT_EQ(p->tiltAngles, (std::vector<float>{0.0f, 45.0f, 90.0f}));
    EXPECT_EQ(p->tiltFactors, (std::vector<float>{1.0f, 0.95f, 0.9f}));
    auto plain = parseIes(validIes(), "lamp.ies");
    ASSERT_TRUE(plain.has_value());
    EXPECT_EQ(p->candela, plain->candela);  // the tilt is kept, not applied
    EXPECT_EQ(p->verticalAngles, plain->verticalAngles);
    // Errors in the block name its line and value.
    EXPECT_EQ(parseError(replaceLine(validIes(), 4, "TILT=INCLUDE\n4\n3\n0 45 90\n1 1 1")),
              "'lamp.ies':5: expected a lamp-to-luminaire geometry of 1, 2 or 3, found 4");
    EXPECT_EQ(parseError(replaceLine(validIes(), 4, "TILT=INCLUDE\n1\n3\n0 90 45\n1 1 1")),
              "'lamp.ies':7: expected tilt angles in increasing order, found 45 after 90");
    EXPECT_EQ(parseError(replaceLine(validIes(), 4, "TILT=INCLUDE\n1\n2\n0 90\n1 -0.5")),
              "'lamp.ies':8: expected a tilt multiplying factor >= 0, found -0.5");
    EXPECT_EQ(parseError(replaceLine(validIes(), 4, "TILT=")),
              "'lamp.ies':4: expected 'TILT=NONE', 'TILT=INCLUDE' or 'TILT=<file>', found 'TILT='");
    // TILT=<file>: parseIes keeps the name; loadIes reads the file beside the IES file.
    auto named = parseIes(replaceLine(validIes(), 4, "TILT=lamp_tilt.dat"), "lamp.ies");
    ASSERT_TRUE(named.has_value()) << named.error().message;
    EXPECT_EQ(named->tilt, "lamp_tilt.dat");
    const std::filesystem::path dir = std::filesystem::path(RG_TEST_TMP) / "ies_tilt";
    std::filesystem::create_directories(dir);
    std::ofstream(dir / "lamp.ies") << replaceLine(validIes(), 4, "TILT=lamp_tilt.dat");
    std::filesystem::remove(dir / "lamp_tilt.dat");
    auto missing = loadIes(dir / "lamp.ies");
    ASSERT_FALSE(missing.has_value());
    EXPECT_NE(missing.error().message.find("TILT=lamp_tilt.dat: no such tilt file"),
              std::string::npos)
        << missing.error().message;
    std::ofstream(dir / "lamp_tilt.dat") << "3\n2\n0 90\n1 0.8\n";
    auto loaded = loadIes(dir / "lamp.ies");
    ASSERT_TRUE(loaded.has_value()) << loaded.error().message;
    EXPECT_EQ(loaded->tiltGeometry, 3);
    EXPECT_EQ(loaded->tiltFactors, (std::vector<float>{1.0f, 0.8f}));
    std::ofstream(dir / "lamp_tilt.dat") << "3\n2\n0 90\n1\n";
    auto truncated = loadIes(dir / "lamp.ies");
    ASSERT_FALSE(truncated.has_value());
    EXPECT_NE(truncated.error().message.find(
                  "lamp_tilt.dat':4: truncated file: expected tilt multiplying factor 2 of 2"),
              std::string::npos)
        << truncated.error().message;
}

TEST(Ies, ErrorUnknownPhotometricType) {
    EXPECT_EQ(parseError(replaceLine(validIes(), 5, "1 1000 1 5 2 4 2 0 0 0")),
              "'lamp.ies':5: expected photometric type 1 (C), 2 (B) or 3 (A), found 4");
}

TEST(Ies, ParsesLm63_2019) {
    // "IES:LM-63-2019"; the second value after the ballast factor is the file generation type.
    std::string text = replaceLine(validIes(), 1, "IES:LM-63-2019");
    text = replaceLine(text, 6, "1 1.00001 10");
    auto p = parseIes(text, "lamp.ies");
    ASSERT_TRUE(p.has_value()) << p.error().message;
    EXPECT_EQ(p->format, IesFormat::Lm63_2019);
    EXPECT_EQ(toString(p->format), "LM-63-2019");
    EXPECT_FLOAT_EQ(p->fileGenerationType, 1.00001f);
    EXPECT_FLOAT_EQ(p->ballastLampFactor, 1.0f);
    EXPECT_EQ(p->candela.size(), 10u);
}

// A type A or B table over −90..90° in 30° steps, each value telling its angles apart.
std::string aimedIes(int type, const std::string& horizontal = "-90 -60 -30 0 30 60 90",
                     const std::string& vertical = "-90 -60 -30 0 30 60 90", bool uniform = false) {
    std::istringstream hs(horizontal), vs(vertical);
    std::vector<double> h, v;
    for (double x; hs >> x;) h.push_back(x);
    for (double x; vs >> x;) v.push_back(x);
    std::ostringstream o;
    o << "IESNA:LM-63-2002\n[TEST] aimed\nTILT=NONE\n1 -1 1 " << v.size() << " " << h.size() << " "
      << type << " 2 0 0 0\n1 1 10\n"
      << vertical << "\n"
      << horizontal << "\n";
    for (double a : h) {
        for (double b : v) o << (uniform ? 100.0 : 1000.0 + 10.0 * a + b) << " ";
        o << "\n";
    }
    return o.str();
}

// The type C angles (degrees) of light-space direction d, as evaluateDegrees takes them.
std::pair<double, double> typeCAngles(glm::dvec3 d) {
    d = glm::normalize(d);
    return {std::atan2(d.y, d.x) * 180.0 / kPi,
            std::acos(std::clamp(d.z, -1.0, 1.0)) * 180.0 / kPi};
}

TEST(Ies, TypesAAndBAimAlongTheLightsDirection) {
    // Type B: polar axis x, d = (sin H, cos H sin V, cos H cos V); type A: polar axis y,
    // d = (cos V sin H, sin V, cos V cos H) (graph/lighting/ies.h). At every table direction
    // (poles excluded: there one angle is undefined) the light-space lookup returns the table's value.
    for (int type : {2, 3}) {
        auto p = parseIes(aimedIes(type), "aimed.ies");
        ASSERT_TRUE(p.has_value()) << p.error().message;
        EXPECT_EQ(p->photometricType, type);
        EXPECT_FALSE(p->mirrorHorizontal);
        int checked = 0;
        for (double H = -60; H <= 60; H += 30)
            for (double V = -60; V <= 60; V += 30) {
                const double h = deg(H), v = deg(V);
                const glm::dvec3 d = type == 2 ? glm::dvec3(std::sin(h), std::cos(h) * std::sin(v),
                                                            std::cos(h) * std::cos(v))
                                               : glm::dvec3(std::cos(v) * std::sin(h), std::sin(v),
                                                            std::cos(v) * std::cos(h));
                const glm::dvec2 back = aimedAngles(type, d);
                EXPECT_NEAR(back.x, H, 1e-9);
                EXPECT_NEAR(back.y, V, 1e-9);
                const auto [ch, cv] = typeCAngles(d);
                EXPECT_NEAR(evaluateDegrees(*p, ch, cv), 1000.0 + 10.0 * H + V, 1e-6)
                    << "type " << type << " H " << H << " V " << V;
                ++checked;
            }
        EXPECT_EQ(checked, 25);
        // The aiming axis is the light's direction (type C's nadir); behind the luminaire, nothing.
        EXPECT_NEAR(evaluateDegrees(*p, 0.0, 0.0), 1000.0, 1e-9);
        EXPECT_EQ(evaluateDegrees(*p, 0.0, 135.0), 0.0);
        EXPECT_EQ(evaluateDegrees(*p, 77.0, 180.0), 0.0);
        // Positive H towards +x (the light's axis), positive V towards +y.
        const double towardsX = evaluateDegrees(*p, 0.0, 30.0),
                     towardsY = evaluateDegrees(*p, 90.0, 30.0);
        EXPECT_NEAR(towardsX, 1000.0 + 10.0 * 30.0, 1e-6) << type;
        EXPECT_NEAR(towardsY, 1000.0 + 30.0, 1e-6) << type;
    }
    // The two differ off the axes: 45° between +x and +y at 40° from the aim.
    auto b = parseIes(aimedIes(2), "b.ies"), a = parseIes(aimedIes(3), "a.ies");
    ASSERT_TRUE(a && b);
    const glm::dvec3 d(std::sin(deg(40)) * std::cos(deg(45)), std::sin(deg(40)) * std::sin(deg(45)),
                       std::cos(deg(40)));
    const glm::dvec2 angB = aimedAngles(2, d), angA = aimedAngles(3, d);
    EXPECT_NEAR(angB.x, angA.y, 1e-9);  // the quarter turn swaps the roles...
    EXPECT_NEAR(angB.y, angA.x, 1e-9);  // ...for a direction on the diagonal
    EXPECT_GT(std::abs(angB.x - angB.y), 1.0);
}

TEST(Ies, TypeBMirrorsATableThatStartsAtZero) {
    auto p = parseIes(aimedIes(2, "0 30 60 90", "0 30 60 90"), "half.ies");
    ASSERT_TRUE(p.has_value()) << p.error().message;
    EXPECT_TRUE(p->mirrorHorizontal);
    EXPECT_TRUE(p->mirrorVertical);
    for (double H : {-60.0, -30.0, 30.0, 60.0})
        for (double V : {-60.0, -30.0, 30.0, 60.0}) {
            const double h = deg(H), v = deg(V);
            const auto [ch, cv] =
                typeCAngles({std::sin(h), std::cos(h) * std::sin(v), std::cos(h) * std::cos(v)});
            EXPECT_NEAR(evaluateDegrees(*p, ch, cv), 1000.0 + 10.0 * std::abs(H) + std::abs(V),
                        1e-6)
                << H << " " << V;
        }
}

TEST(Ies, TypeBUniformTableSendsHalfAnIsotropicSourcesFlux) {
    // 100 cd over |H|, |V| ≤ 90°: exactly the front hemisphere, 2π · 100 lm.
    for (int type : {2, 3}) {
        auto p = parseIes(aimedIes(type, "-90 -60 -30 0 30 60 90", "-90 -60 -30 0 30 60 90", true),
                          "flood.ies");
        ASSERT_TRUE(p.has_value()) << p.error().message;
        EXPECT_NEAR(integrateLumens(*p), 2.0 * kPi * 100.0, 0.005 * 2.0 * kPi * 100.0) << type;
    }
}

TEST(Ies, ErrorTypeBAnglesOutsideTheAimedRange) {
    EXPECT_EQ(parseError(aimedIes(2, "-90 0 90", "-45 0 45"), "flood.ies"),
              "'flood.ies':6: expected vertical angles from -90 or 0 to at most 90 degrees (type "
              "B), found -45..45");
    EXPECT_EQ(parseError(aimedIes(3, "0 90 120", "0 45 90"), "flood.ies"),
              "'flood.ies':7: expected horizontal angles from -90 or 0 to at most 90 degrees (type "
              "A), found 0..120");
}

TEST(Ies, ErrorNonNumericValues) {
    EXPECT_EQ(parseError(replaceLine(validIes(), 9, "100 90 seventy 40 0")),
              "'lamp.ies':9: expected a number for candela value 3 of 10 (horizontal angle 0, "
              "vertical angle 45), found 'seventy'");
    EXPECT_EQ(parseError(replaceLine(validIes(), 7, "0 22.5 4x5 67.5 90")),
              "'lamp.ies':7: expected a number for vertical angle 3 of 5, found '4x5'");
    EXPECT_EQ(parseError(replaceLine(validIes(), 5, "1 1000 one 5 2 1 2 0 0 0")),
              "'lamp.ies':5: expected a number for the candela multiplier (value 3 of 10 after "
              "TILT), found 'one'");
    EXPECT_EQ(parseError(replaceLine(validIes(), 5, "1 1000 1 5.5 2 1 2 0 0 0")),
              "'lamp.ies':5: expected an integer for the number of vertical angles (value 4 of 10 "
              "after TILT), found '5.5'");
    EXPECT_EQ(parseError(replaceLine(validIes(), 9, "100 90 70 1e39 0")),
              "'lamp.ies':9: expected a number for candela value 4 of 10 (horizontal angle 0, "
              "vertical angle 67.5), found '1e39'");
    EXPECT_EQ(parseError(replaceLine(validIes(), 6, "1 1 nan")),
              "'lamp.ies':6: expected a number for the input watts (value 3 of 3 on the second "
              "line after TILT), found 'nan'");
}

TEST(Ies, ErrorAnglesNotIncreasing) {
    EXPECT_EQ(parseError(replaceLine(validIes(), 7, "0 22.5 67.5 45 90")),
              "'lamp.ies':7: expected vertical angles in increasing order, found 45 after 67.5");
    EXPECT_EQ(parseError(replaceLine(validIes(), 8, "90 0")),
              "'lamp.ies':8: expected horizontal angles in increasing order, found 0 after 90");
    EXPECT_EQ(
        parseError(replaceLine(validIes(), 7, "0 22.5 45 67.5 190")),
        "'lamp.ies':7: expected vertical angles within 0..180 degrees (type C), found 0..190");
    EXPECT_EQ(parseError(replaceLine(validIes(), 8, "45 135")),
              "'lamp.ies':8: expected horizontal angles 0 (rotationally symmetric), 0..90, 0..180, "
              "0..360 or 90..270 degrees "
              "(type C), found 45..135");
}

TEST(Ies, ErrorNegativeCandela) {
    EXPECT_EQ(parseError(replaceLine(validIes(), 10, "100 80 -3 30 0")),
              "'lamp.ies':10: expected a non-negative candela value at horizontal angle 90, "
              "vertical angle 45, found -3");
}

TEST(Ies, ErrorTruncatedFile) {
    const std::string text = validIes();
    // Cut inside the candela values, after 7 of 10.
    EXPECT_EQ(parseError(text.substr(0, text.rfind("60 30 0"))),
              "'lamp.ies':10: truncated file: expected 10 candela values (2 horizontal x 5 "
              "vertical angles), found 7");
    // Cut inside the lamp values.
    EXPECT_EQ(parseError("IESNA:LM-63-2002\nTILT=NONE\n1 1000 1 5\n"),
              "'lamp.ies':3: truncated file: expected the number of horizontal angles (value 5 of "
              "10 after TILT), found the end of "
              "the file");
    // Cut right after the vertical angles.
    EXPECT_EQ(parseError(text.substr(0, text.find("0 90\n"))),
              "'lamp.ies':7: truncated file: expected 2 horizontal angles, found 0");
    // Extra values after the table.
    EXPECT_EQ(
        parseError(text + "5 5\n"),
        "'lamp.ies':9: expected 10 candela values (2 horizontal x 5 vertical angles), found 12");
}

TEST(Ies, ErrorUnknownFormatLineAndBadHeaderValues) {
    EXPECT_EQ(parseError(replaceLine(validIes(), 1, "IESNA:LM-63-2019")),
              "'lamp.ies':1: unknown IES format 'IESNA:LM-63-2019', expected one of: "
              "'IES:LM-63-2019', 'IESNA:LM-63-2002', "
              "'IESNA:LM-63-1995', 'IESNA91', or no format line (LM-63-1986)");
    EXPECT_EQ(parseErrorCode(replaceLine(validIes(), 1, "IESNA:LM-63-2019")),
              ErrorCode::Unsupported);
    EXPECT_EQ(
        parseError(replaceLine(validIes(), 2, "[TEST nothing closes")),
        "'lamp.ies':2: expected a keyword line '[KEYWORD] text', found '[TEST nothing closes'");
    EXPECT_EQ(parseError(replaceLine(validIes(), 5, "1 1000 1 0 2 1 2 0 0 0")),
              "'lamp.ies':5: expected a positive number of vertical angles, found 0");
    EXPECT_EQ(parseError(replaceLine(validIes(), 5, "1 1000 0 5 2 1 2 0 0 0")),
              "'lamp.ies':5: expected a positive candela multiplier, found 0");
    EXPECT_EQ(parseError(replaceLine(validIes(), 5, "1 1000 1 5 2 1 3 0 0 0")),
              "'lamp.ies':5: expected units type 1 (feet) or 2 (meters), found 3");
    EXPECT_EQ(
        parseError(replaceLine(validIes(), 5, "1 -5 1 5 2 1 2 0 0 0")),
        "'lamp.ies':5: expected the lumens per lamp (or -1 for absolute photometry), found -5");
}

TEST(Ies, LoadReportsAMissingFile) {
    auto p = loadIes(iesPath("no_such_lamp.ies"));
    ASSERT_FALSE(p.has_value());
    EXPECT_EQ(p.error().code, ErrorCode::NotFound);
    EXPECT_EQ(p.error().message, "'" + iesPath("no_such_lamp.ies") + "': no such IES file");
}

TEST(Ies, BadInputNeverCrashes) {
    // Every prefix of a valid file either parses or fails with a message naming the file.
    const std::string text = validIes();
    for (size_t n = 0; n < text.size(); ++n) {
        auto p = parseIes(text.substr(0, n), "cut.ies");
        if (!p) {
            EXPECT_EQ(p.error().message.rfind("'cut.ies':", 0), 0u) << p.error().message;
        }
    }
    // Garbage of every byte value.
    std::string noise;
    for (int i = 0; i < 2000; ++i) noise += static_cast<char>((i * 7919) % 256);
    EXPECT_FALSE(parseIes(noise, "noise.ies").has_value());
}

TEST(Ies, SymmetricExpansion) {
    // Quadrant: 0, 22.5, …, 90 → 0..360 in 22.5° steps, each column mirrored.
    const IesProfile q = loadOrFail("wallwash_1995.ies");
    const IesProfile qe = expandSymmetry(q);
    EXPECT_EQ(qe.symmetry, IesSymmetry::None);
    ASSERT_EQ(qe.horizontalAngles.size(), 17u);
    for (size_t i = 0; i < 17; ++i)
        EXPECT_EQ(qe.horizontalAngles[i], 22.5f * static_cast<float>(i));
    const auto column = [](const IesProfile& p, size_t h) {
        const size_t n = p.verticalAngles.size();
        return std::vector<float>(p.candela.begin() + static_cast<long>(h * n),
                                  p.candela.begin() + static_cast<long>((h + 1) * n));
    };
    EXPECT_EQ(column(qe, 7), column(q, 1));   // 157.5 = 180 − 22.5
    EXPECT_EQ(column(qe, 9), column(q, 1));   // 202.5 = 180 + 22.5
    EXPECT_EQ(column(qe, 15), column(q, 1));  // 337.5 = 360 − 22.5
    EXPECT_EQ(column(qe, 12), column(q, 4));  // 270 ↔ 90
    EXPECT_EQ(column(qe, 16), column(q, 0));  // 360 ↔ 0

    // Bilateral 0..180 → 0..360 in 45° steps, 225 ↔ 135.
    const IesProfile b = loadOrFail("bilateral_1991.ies");
    const IesProfile be = expandSymmetry(b);
    ASSERT_EQ(be.horizontalAngles.size(), 9u);
    EXPECT_EQ(be.horizontalAngles[5], 225.0f);
    EXPECT_EQ(std::vector<float>(be.candela.begin() + 5 * 4, be.candela.begin() + 6 * 4),
              std::vector<float>(b.candela.begin() + 3 * 4, b.candela.begin() + 4 * 4));

    // 90..270 → mirrored about the 90–270 plane: 45 ↔ 135, 0 ↔ 180, 315 ↔ 225.
    const IesProfile m = loadOrFail("pendant_2002.ies");
    const IesProfile me = expandSymmetry(m);
    EXPECT_EQ(me.horizontalAngles, (std::vector<float>{0, 45, 90, 135, 180, 225, 270, 315, 360}));
    for (auto [a, bAngle] : {std::pair{0.0, 180.0}, std::pair{45.0, 135.0}, std::pair{315.0, 225.0},
                             std::pair{360.0, 180.0}})
        for (float v : m.verticalAngles)
            EXPECT_EQ(evaluateDegrees(me, a, v), evaluateDegrees(m, bAngle, v)) << a << " " << v;

    // Rotational → {0, 360}, the single column twice.
    const IesProfile r = loadOrFail("downlight_2002.ies");
    const IesProfile re = expandSymmetry(r);
    EXPECT_EQ(re.horizontalAngles, (std::vector<float>{0, 360}));
    EXPECT_EQ(column(re, 1), r.candela);

    // evaluate() agrees everywhere between a profile and its expansion.
    for (const IesProfile* p : {&q, &b, &m, &r}) {
        const IesProfile e = expandSymmetry(*p);
        for (double h = -30.0; h <= 400.0; h += 7.3)
            for (double v = 0.0; v <= 180.0; v += 6.1)
                EXPECT_NEAR(evaluateDegrees(e, h, v), evaluateDegrees(*p, h, v), 1e-3)
                    << p->fileName << " " << h << " " << v;
    }
}

TEST(Ies, EvaluateIsExactAtTableAnglesAndBilinearBetween) {
    const IesProfile p = loadOrFail("wallwash_1995.ies");
    const size_t nV = p.verticalAngles.size();
    for (size_t h = 0; h < p.horizontalAngles.size(); ++h) {
        for (size_t v = 0; v < nV; ++v) {
            const double table = p.candela[h * nV + v];
            EXPECT_EQ(evaluateDegrees(p, p.horizontalAngles[h], p.verticalAngles[v]), table);
            EXPECT_NEAR(evaluate(p, static_cast<float>(deg(p.horizontalAngles[h])),
                                 static_cast<float>(deg(p.verticalAngles[v]))),
                        table, 1e-4 * p.maxCandela);
        }
    }
    // Between angles: linear along each axis, bilinear inside a cell.
    const auto c = [&](size_t h, size_t v) { return static_cast<double>(p.candela[h * nV + v]); };
    EXPECT_NEAR(evaluateDegrees(p, 22.5, 11.25), 0.5 * (c(1, 0) + c(1, 1)), 1e-9);
    EXPECT_NEAR(evaluateDegrees(p, 33.75, 45.0), 0.5 * (c(1, 2) + c(2, 2)), 1e-9);
    const double wh = (30.0 - 22.5) / 22.5, wv = (50.0 - 45.0) / 22.5;
    EXPECT_NEAR(
        evaluateDegrees(p, 30.0, 50.0),
        (1 - wh) * ((1 - wv) * c(1, 2) + wv * c(1, 3)) + wh * ((1 - wv) * c(2, 2) + wv * c(2, 3)),
        1e-9);
    // Quadrant folding: 180 − 30, 180 + 30, 360 − 30 and −30 are all 30.
    for (double h : {150.0, 210.0, 330.0, -30.0, 390.0})
        EXPECT_NEAR(evaluateDegrees(p, h, 50.0), evaluateDegrees(p, 30.0, 50.0), 1e-9);

    // A downlight measured to 90° sends nothing above it.
    const IesProfile down = loadOrFail("downlight_2002.ies");
    EXPECT_EQ(evaluateDegrees(down, 0.0, 90.0), 0.0);
    EXPECT_EQ(evaluateDegrees(down, 123.0, 120.0), 0.0);
    EXPECT_EQ(evaluateDegrees(down, 77.0, 0.0), 850.0);  // rotationally symmetric
    // Full 0..360 data: 315° lies between the 270° and 360° columns.
    const IesProfile street = loadOrFail("street_1986.ies");
    EXPECT_NEAR(evaluateDegrees(street, 315.0, 0.0), 0.5 * (450.0 + 650.0), 1e-9);
}

TEST(Ies, IntegratedLumensOfAnIsotropicSource) {
    // 100 cd in every direction is 4π · 100 lm.
    const std::string text =
        "IESNA:LM-63-2002\nTILT=NONE\n1 1256.6 1 3 1 1 2 0 0 0\n1 1 0\n0 90 180\n0\n100 100 100\n";
    auto p = parseIes(text, "isotropic.ies");
    ASSERT_TRUE(p.has_value()) << p.error().describe();
    EXPECT_NEAR(integrateLumens(*p), 4 * kPi * 100, 0.05);
}

TEST(Ies, BakedTextureIsNormalisedByTheMaximumCandela) {
    // lst:5: (θ, cos φ), values I / I_max. A ring profile peaking at 90°: with an odd height one row
    // lies exactly at cos φ = 0, so the texture's maximum is exactly 1.
    const std::string ring =
        "IESNA:LM-63-2002\nTILT=NONE\n1 1000 1 5 1 1 2 0 0 0\n1 1 0\n0 45 90 135 180\n0\n"
        "10 200 800 200 10\n";
    auto p = parseIes(ring, "ring.ies");
    ASSERT_TRUE(p.has_value()) << p.error().describe();
    const IesTexture t = bakeIes(*p, 64, 129);
    ASSERT_EQ(t.texels.size(), 64u * 129u);
    EXPECT_EQ(t.maxCandela, 800.0f);
    EXPECT_EQ(*std::max_element(t.texels.begin(), t.texels.end()), 1.0f);
    EXPECT_EQ(t.texels[64 * 64 + 10], 1.0f);  // the middle row
    for (float v : t.texels) {
        EXPECT_GE(v, 0.0f);
        EXPECT_LE(v, 1.0f);
    }

    // The wall washer peaks at the nadir (cos φ = 1), which no texel centre reaches: the last row is
    // at cos φ = 1 − 1/256, i.e. φ = 5.1° (cos φ rows are sparse in angle near the poles), where the
    // profile is at 97.7 % of its peak. texel × maxCandela is the intensity there.
    const IesProfile w = loadOrFail("wallwash_1995.ies");
    const IesTexture wt = bakeIes(w, 256, 256);
    const float wmax = *std::max_element(wt.texels.begin(), wt.texels.end());
    EXPECT_LT(wmax, 1.0f);
    EXPECT_GT(wmax, 0.97f);
    const double rowPhi = std::acos(2.0 * (255 + 0.5) / 256 - 1.0) * 180.0 / kPi;
    EXPECT_NEAR(rowPhi, 5.07, 0.01);
    EXPECT_NEAR(wt.texels[255 * 256 + 0] * wt.maxCandela,
                evaluateDegrees(w, 360.0 * 0.5 / 256, rowPhi), 1e-3);
    EXPECT_EQ(wmax, wt.texels[255 * 256 + 0]);

    // lst:5 in use: a light pointing down world −y (its nadir, light-space +z) with horizontal 0° along
    // world +x. The attenuation times maxCandela follows the profile within the texture's resolution.
    const glm::mat3 lightToWorld(glm::vec3(1, 0, 0), glm::vec3(0, 0, 1),
                                 glm::vec3(0, -1, 0));  // columns: x, y, z
    const glm::mat3 worldToLight = glm::transpose(lightToWorld);
    double worst = 0.0;
    for (int i = 0; i < 500; ++i) {
        const double a = 2 * kPi * ((i * 0.618034) - std::floor(i * 0.618034)),
                     z = -1.0 + 2.0 * (i + 0.5) / 500;
        const glm::vec3 dirLight(static_cast<float>(std::sqrt(1 - z * z) * std::cos(a)),
                                 static_cast<float>(std::sqrt(1 - z * z) * std::sin(a)),
                                 static_cast<float>(z));
        const glm::vec3 L = -(lightToWorld * dirLight);  // from the point back to the light
        const double viaTexture = getIESProfileAttenuation(L, worldToLight, wt) * wt.maxCandela;
        const double direct = evaluate(w, static_cast<float>(std::atan2(dirLight.y, dirLight.x)),
                                       static_cast<float>(std::acos(z)));
        worst = std::max(worst, std::abs(viaTexture - direct));
    }
    std::printf("IES texture 256x256 vs table, worst |difference| %.2f cd of %.0f cd\n", worst,
                static_cast<double>(w.maxCandela));
    EXPECT_LT(worst, 0.02 * w.maxCandela);
    // Straight down the nadir (v = 1) and straight up (v = 0) the sampler clamps to the edge rows.
    const glm::vec3 up(0, 1, 0);  // L for a point below the light: it sees the light above it
    EXPECT_FLOAT_EQ(getIESProfileAttenuation(up, worldToLight, wt), wt.texels[255 * 256 + 128]);
    EXPECT_FLOAT_EQ(getIESProfileAttenuation(-up, worldToLight, wt), wt.texels[0 * 256 + 128]);
    EXPECT_GT(getIESProfileAttenuation(up, worldToLight, wt), 0.97f);
    EXPECT_LT(getIESProfileAttenuation(-up, worldToLight, wt), 10.0f / 1024.0f);
}

// IES photometric profiles (seed 000 §4.5, eq:27, lst:5): an IESNA LM-63 parser, evaluation of the
// candela table, and the baked, max-normalised 2D texture that the shaders sample as an attenuation.
//
// Formats read: LM-63-1986 (no format line), LM-63-1991 ("IESNA91"), LM-63-1995 ("IESNA:LM-63-1995"),
// LM-63-2002 ("IESNA:LM-63-2002") and LM-63-2019 ("IES:LM-63-2019", whose second value after the
// ballast factor is the file generation type); keyword lines ([TEST], [MANUFAC], … with [MORE]
// continuations) are kept. TILT=NONE, TILT=INCLUDE and TILT=<file> (the tilt data is read and kept;
// rendering uses the luminaire as photometered). Photometric types C (1), B (2) and A (3).
// Numbers may be split across any number of lines and separated by blanks and/or commas.
//
// Angles: IES tables are in degrees. Type C: the vertical angle is measured from the nadir (0°, the
// direction a downlight or spot shines) to the zenith (180°); the horizontal angle turns around the
// vertical axis, 0° along the luminaire's length. In the light space of lst:5 the nadir is +z,
// horizontal 0° is +x and horizontal 90° is +y, so the seed's φ is the vertical angle
// (cos φ = z) and its θ the horizontal one (θ = atan2(y, x)).
//
// Types A and B (floodlights, automotive lamps) are measured around the aiming axis, which rgraph
// puts where type C puts the nadir (+z, the light's direction), with positive horizontal angles
// towards +x (the light's axis) and positive vertical angles towards +y. Type B's polar axis is x:
// a vertical angle V turns the measuring plane about it, a horizontal angle H leaves that plane
// towards x, so d = (sin H, cos H sin V, cos H cos V). Type A is type B turned a quarter about the
// aiming axis, its polar axis y: d = (cos V sin H, sin V, cos V cos H). Both tables span −90..90°
// of each angle, or 0..90° for a distribution mirrored onto the negative side; directions outside
// them (behind the luminaire) get no light.
//
// Ownership: IesProfile and IesTexture are plain values. Thread-safe: no shared state.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "core/result.h"

namespace rg {

enum class IesFormat { Lm63_1986, Lm63_1991, Lm63_1995, Lm63_2002, Lm63_2019 };
// "LM-63-1986" … "LM-63-2019".
std::string_view toString(IesFormat format);

// How the horizontal angles cover the full circle (type C, LM-63-2002 §3.20).
enum class IesSymmetry {
    Rotational,   // a single horizontal angle (0°): the same in every direction around the axis
    Quadrant,     // 0°..90°: symmetric in each quadrant
    Bilateral,    // 0°..180°: symmetric about the 0°–180° plane
    Bilateral90,  // 90°..270°: symmetric about the 90°–270° plane
    None,         // 0°..360° (or 0°..last > 180°, the gap to 360° interpolated to 0°)
};
std::string_view toString(IesSymmetry symmetry);

struct IesKeyword {
    std::string name;   // "TEST", "MANUFAC", …; empty for LM-63-1986 label lines
    std::string value;  // [MORE] lines are appended after a '\n'
};

struct IesProfile {
    std::string fileName;
    IesFormat format = IesFormat::Lm63_2002;
    std::vector<IesKeyword> keywords;

    int numberOfLamps = 1;
    float lumens = 0.0f;      // lumens per lamp as declared; -1 means absolute photometry
    float multiplier = 1.0f;  // the candela multiplier as declared (already applied to `candela`)
    int photometricType = 1;  // 1 = type C, 2 = type B, 3 = type A
    int unitsType = 2;        // 1 = feet, 2 = metres (of the luminous opening below)
    float width = 0.0f, length = 0.0f, height = 0.0f;  // luminous opening, in unitsType
    float ballastFactor = 1.0f;
    float ballastLampFactor = 1.0f;  // "future use" since LM-63-1995; kept as read
    float fileGenerationType =
        0.0f;  // LM-63-2019's value in that place (e.g. 1.00001), kept as read
    float inputWatts = 0.0f;

    std::vector<float> verticalAngles;    // degrees, increasing, within 0..180
    std::vector<float> horizontalAngles;  // degrees, increasing, as declared (see symmetry)
    // Luminous intensity in cd: the file's values times the multiplier. [h][v], i.e.
    // candela[h * verticalAngles.size() + v]. Ballast factors are not applied.
    std::vector<float> candela;
    float maxCandela = 0.0f;                         // cd, the largest entry of `candela`
    IesSymmetry symmetry = IesSymmetry::Rotational;  // type C; types A and B: None
    // Types A and B: the table starts at 0° and is mirrored onto the negative side.
    bool mirrorHorizontal = false, mirrorVertical = false;
    // TILT (LM-63-2002 §3.10): "NONE", "INCLUDE" (the tilt data follows the TILT line) or the name
    // of a tilt file (read by loadIes from the IES file's folder). The data — lamp-to-luminaire
    // geometry (1..3), tilt angles (degrees) and their candela multipliers — is kept as read;
    // rendering uses the luminaire as photometered (no tilt applied).
    std::string tilt = "NONE";
    int tiltGeometry = 0;
    std::vector<float> tiltAngles, tiltFactors;
};

// Parses the tilt data of a TILT=<file> tilt file (or the block after TILT=INCLUDE): geometry,
// count, angles, multiplying factors, into `profile`. fileName names it in errors.
Result<void> parseIesTilt(std::string_view text, const std::string& fileName, IesProfile& profile);

// Parses an LM-63 file's text. fileName is only used in error messages, which read
// "'<fileName>':<line>: <what was expected>, found <what was there>".
Result<IesProfile> parseIes(std::string_view text, const std::string& fileName);
// Reads and parses a file (Io/NotFound errors name the path).
Result<IesProfile> loadIes(const std::filesystem::path& path);

// Luminous intensity (cd) towards horizontal angle theta and vertical angle phi (radians), by
// bilinear interpolation of the candela table in (horizontal, vertical) degrees, after folding
// theta by the profile's symmetry. Outside the vertical range of the table (e.g. above 90° for a
// 0°..90° downlight) the intensity is 0.
float evaluate(const IesProfile& profile, float theta, float phi);
// The same with angles in degrees, in double: at table angles it returns the table's value exactly.
// The angles are always type C's in light space (the parametrisation of the baked texture); a type
// A or B profile is looked up at the same direction's own angles (aimedAngles).
double evaluateDegrees(const IesProfile& profile, double horizontalDegrees, double verticalDegrees);
// A light-space direction's (horizontal, vertical) angles in degrees for photometric type B (2)
// or A (3), as the header above defines them.
glm::dvec2 aimedAngles(int photometricType, glm::dvec3 direction);

// The profile with its symmetry unfolded: horizontal angles from 0° to 360° (both included: the
// 360° column repeats 0°), every mirrored table angle kept, values copied from the table.
// Rotationally symmetric profiles become {0°, 360°}. evaluate() gives the same on both.
IesProfile expandSymmetry(const IesProfile& profile);

// Luminous flux (lm) of the candela distribution, ∫ I dω (midpoint rule in the vertical angle and
// the horizontal angle, steps × steps). For relative photometry it is the luminaire's flux, which
// the declared lamp lumens bound from above.
double integrateLumens(const IesProfile& profile, int steps = 720);

// lst:5: the profile resampled in the (θ, cos φ) parametrisation, normalised by the maximum
// candela, so one texture serves as an intensity profile (lightColor = color · maxCandela) and as
// a mask (lightColor = color · Φ / 4π) (eq:27). Texel (i, j) is at the centre of its cell:
// θ = 2π (i + 0.5) / width, cos φ = 2 (j + 0.5) / height − 1; sampled with repeat in u and
// clamp-to-edge in v, the texture coordinates of lst:5 then land on the table's values. Values lie
// in [0, 1]; the largest is 1 where the profile's peak falls on a texel centre and slightly less
// otherwise (the texture is point-sampled, never renormalised, so texel × maxCandela stays in cd).
struct IesTexture {
    uint32_t width = 0;         // θ samples (horizontal angle, u)
    uint32_t height = 0;        // cos φ samples (vertical angle, v)
    std::vector<float> texels;  // row-major: texels[j * width + i], R32_SFLOAT
    float maxCandela = 0.0f;    // cd; texel × maxCandela is the intensity
};
IesTexture bakeIes(const IesProfile& profile, uint32_t width = 256, uint32_t height = 256);

// lst:5's texture coordinates of a light-space direction (from the light towards the point):
// u = atan2(y, x) / 2π (in −0.5..0.5, for a repeating sampler), v = z · 0.5 + 0.5.
glm::vec2 iesTexCoord(glm::vec3 lightSpaceDirection);
// What the GPU's bilinear sampler returns at uv (repeat in u, clamp-to-edge in v, texel centres).
float sampleIesTexture(const IesTexture& texture, glm::vec2 uv);
// lst:5: the normalised profile towards the shaded point; L is the unit vector from the point to
// the light, worldToLight rotates world directions into light space.
float getIESProfileAttenuation(glm::vec3 L, const glm::mat3& worldToLight,
                               const IesTexture& texture);

}  // namespace rg

// The scene's lights as the shaders read them (shaders/lib/scene.glsl's Lights block): each light
// converted once on the CPU into the unit its evaluation needs, with its IES profile baked. What
// the GPU scene uploads and the lightmap baker samples.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/result.h"
#include "lighting/ies.h"
#include "scene/scene.h"
#include "shaders/lib/limits.h"

namespace rg::lighting {

// The most lights a scene may have (shaders/lib/limits.h, which the shaders include too): the
// tile lists' 16-bit light indices.
inline constexpr uint32_t kMaxLights = RG_MAX_LIGHTS;
// IES profiles are baked at this size (bakeIes' θ × cos φ texels, seed 000 lst:5), each 256 KiB
// in the scene's light tables; a scene may use this many different profile files.
inline constexpr uint32_t kIesWidth = 256, kIesHeight = 256;
inline constexpr uint32_t kMaxIesProfiles = 16;

// One light as scene.glsl's RgLight (std430: five vec4; see there for every field).
struct GpuLight {
    glm::vec4 positionType{0.0f};
    glm::vec4 directionRange{0.0f};
    glm::vec4 intensity{0.0f};  // rgb: colour × cd / lux / cd/m²; a: IES profile, -1 for none
    glm::vec4 params{0.0f};
    glm::vec4 axis{0.0f};
};
static_assert(sizeof(GpuLight) == 80, "GpuLight must match RgLight's std430 layout");

// scene.glsl's RG_LIGHT_* codes (GpuLight::positionType.w).
enum class GpuLightType : uint8_t {
    Point = 0,
    Spot = 1,
    Sun = 2,
    Sphere = 3,
    Disk = 4,
    Rect = 5,
    Tube = 6
};

// How an IES profile sets a point or spot light's intensity (seed 000 §4.5, eq:27, lst:5): the
// scene's default, for lights whose Light::iesMode is empty.
enum class IesMode {
    Mask,       // the declared intensity (lm → cd as without a profile, or cd) × I / I_max: the
                // profile only shapes the light (the default; lst:5's "mask")
    Intensity,  // the profile's own candela: I_max × I / I_max; the declared intensity is ignored
};

// The scene's lights as the shaders take them, converted once (what GpuScene uploads).
struct GpuLightTable {
    std::vector<GpuLight> lights;      // in the scene's order
    std::vector<IesTexture> profiles;  // one per distinct IES file, kIesWidth × kIesHeight
    std::vector<std::string> profilePaths;
};

// Converts lights to GpuLights (lighting/ and core/light_units do the arithmetic):
// - point, spot: cd; lm → cd by tbl:9 — Φ / 4π, and for spots Frostbite's eq:17, Φ / π (the cone
//   does not change the brightness), or eq:16's exact cone with Light::exactCone. The cone's angle
//   scale and offset of lst:4. With an IES profile (Light::ies: loaded with loadIes, baked with
//   bakeIes), Light::iesMode or else the scene's IesMode; its light space has +z along Light::direction (the profile's nadir)
//   and +x along Light::up made perpendicular to it (horizontal angle 0°) — when they are
//   parallel, as for a light pointing straight down with the default up, +x is direction ×
//   (1, 0, 0): +z for a light pointing down.
// - sun: lux perpendicular to its rays; sin and cos of its angular radius (lst:6).
// - sphere, disk, rect, tube: luminance in cd/m² from lm (tbl:12), nits or EV100 (eq:12) by
//   lighting::areaLightLuminance. A rect's up is made perpendicular to its direction. A disk with
//   a cone (Light::cone, lst:9) gets the spot's angle scale and offset in params.xy and the
//   distance from its centre back to the cone's apex in axis.w; range windows every local light by
//   the distance to its centre (lst:4).
// Colour temperature multiplies the colour (tbl:4). Errors name the light: a unit its type cannot
// have, a size that is not positive, an IES file that does not load, more than kMaxLights lights
// or kMaxIesProfiles profiles.
Result<GpuLightTable> convertLights(const std::vector<Light>& lights,
                                    IesMode iesMode = IesMode::Mask);

}  // namespace rg::lighting

// convertLights: the scene's lights in the shaders' units and layout (light_table.h).
#include "lighting/light_table.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>

#include "core/light_units.h"
#include "lighting/area_lights.h"
#include "lighting/punctual.h"

namespace rg::lighting {

namespace {

std::string lightLabel(const Light& l) {
    return "light '" + l.name + "' (" + lightTypeName(l.type) + ")";
}

// A unit vector perpendicular to `n`: `hint` made perpendicular, or any when they are parallel.
glm::vec3 perpendicularTo(glm::vec3 n, glm::vec3 hint) {
    glm::vec3 p = hint - glm::dot(hint, n) * n;
    if (glm::length(p) < 1e-4f)
        p = glm::cross(n, std::abs(n.y) < 0.99f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0));
    return glm::normalize(p);
}

}  // namespace

Result<GpuLightTable> convertLights(const std::vector<Light>& lights, IesMode iesMode) {
    GpuLightTable table;
    if (lights.size() > kMaxLights)
        return fail(ErrorCode::InvalidInput, "the scene has " + std::to_string(lights.size()) +
                                                 " lights; at most " + std::to_string(kMaxLights) +
                                                 " (the light lists' 16-bit indices)");
    for (const Light& l : lights) {
        const std::string label = lightLabel(l);
        const bool punctual = l.type == LightType::Point || l.type == LightType::Spot;
        const bool sun = l.type == LightType::Directional;
        // seed 000 tbl:8: the units each type takes (as the scene loaders check; a Scene built
        // in C++ may not have been).
        const std::vector<std::string> units =
            punctual ? std::vector<std::string>{"lm", "cd"}
            : sun    ? std::vector<std::string>{"lux"}
                     : std::vector<std::string>{"lm", "nits", "ev100"};
        if (std::find(units.begin(), units.end(), l.unit) == units.end()) {
            std::string list;
            for (const auto& u : units) list += (list.empty() ? "'" : ", '") + u + "'";
            return fail(ErrorCode::InvalidInput, label + ": unit '" + l.unit + "' is not one of " +
                                                     list + " (seed 000 tbl:8)");
        }
        if (!std::isfinite(l.intensity) || (l.unit != "ev100" && l.intensity < 0.0f))
            return fail(
                ErrorCode::InvalidInput,
                label + ": intensity must be a finite number, not negative (" + l.unit + ")");
        if (!l.ies.empty() && !punctual)
            return fail(ErrorCode::InvalidInput,
                        label + ": an IES profile applies to point and spot lights only");
        const glm::vec3 direction =
            glm::length(l.direction) > 0.0f ? glm::normalize(l.direction) : glm::vec3(0, -1, 0);

        glm::vec3 color = l.color;
        if (l.temperatureK > 0) {
            if (!lights::colorTemperatureInRange(l.temperatureK, l.daylight))
                return fail(ErrorCode::InvalidInput,
                            label + ": temperature " + std::to_string(l.temperatureK) +
                                " K is outside the " +
                                (l.daylight ? "daylight locus's 4000-25000 K"
                                            : "black body's 1667-25000 K") +
                                " that colour temperature converts");
            auto rgb = lights::colorTemperatureToRgb(l.temperatureK, l.daylight);
            color *= glm::vec3(static_cast<float>(rgb[0]), static_cast<float>(rgb[1]),
                               static_cast<float>(rgb[2]));
        }
        GpuLight g{};
        // 1/range², at least the smallest normal float: a range so long that it underflows to 0
        // (~1.8e19 m) would read as "no range" on the GPU (the global lights' rule, w <= 0) while
        // the shaders' build counts the light as ranged (passes/shader_program.cpp).
        const float invSqrRange =
            l.range > 0 ? std::max(1.0f / (l.range * l.range), std::numeric_limits<float>::min())
                        : 0.0f;
        g.positionType = glm::vec4(l.position, 0.0f);
        g.directionRange = glm::vec4(direction, invSqrRange);
        g.intensity.a = -1.0f;
        GpuLightType type = GpuLightType::Point;
        double value = l.intensity;  // cd, lux or cd/m² once converted
        switch (l.type) {
            case LightType::Point:
            case LightType::Spot: {
                type = l.type == LightType::Point ? GpuLightType::Point : GpuLightType::Spot;
                // tbl:9; spots by eq:17 (Φ / π), or eq:16's exact cone when the light asks for it.
                if (l.unit == "lm")
                    value = l.type == LightType::Point
                                ? lights::pointIntensityFromLumens(l.intensity)
                                : lights::spotIntensityFromLumens(l.intensity, l.outerAngle,
                                                                  l.exactCone);
                // lst:4: the cone as a scale and offset of cos θ; a point light has none (0, 1).
                lighting::AngleScaleOffset cone;
                if (l.type == LightType::Spot)
                    cone = lighting::spotAngleScaleOffset(l.innerAngle, l.outerAngle);
                g.params = glm::vec4(cone.scale, cone.offset, 0.0f, 0.0f);
                if (!l.ies.empty()) {
                    auto it =
                        std::find(table.profilePaths.begin(), table.profilePaths.end(), l.ies);
                    if (it == table.profilePaths.end()) {
                        if (table.profiles.size() >= kMaxIesProfiles)
                            return fail(ErrorCode::InvalidInput,
                                        label + ": the scene uses more than " +
                                            std::to_string(kMaxIesProfiles) +
                                            " different IES profiles");
                        auto profile = loadIes(l.ies);
                        if (!profile)
                            return fail(profile.error().code,
                                        label + ": " + profile.error().message,
                                        profile.error().reasons);
                        if (profile->maxCandela <= 0.0f)
                            return fail(ErrorCode::InvalidInput,
                                        label + ": the IES profile '" + l.ies +
                                            "' sends no light (its largest candela value is 0)");
                        table.profiles.push_back(bakeIes(*profile, kIesWidth, kIesHeight));
                        table.profilePaths.push_back(l.ies);
                        it = table.profilePaths.end() - 1;
                    }
                    const auto index = static_cast<size_t>(it - table.profilePaths.begin());
                    g.intensity.a = static_cast<float>(index);
                    // eq:27: I is either the profile's maximum candela or the user's intensity (mask).
                    if (!l.iesMode.empty() && l.iesMode != "mask" && l.iesMode != "intensity")
                        return fail(ErrorCode::InvalidInput, label + ": ies_mode '" + l.iesMode +
                                                                 "' is not 'mask' or 'intensity'");
                    const bool profileIntensity = l.iesMode.empty() ? iesMode == IesMode::Intensity
                                                                    : l.iesMode == "intensity";
                    if (profileIntensity) value = table.profiles[index].maxCandela;
                    // lst:5's light space: z the nadir (the light's direction), x horizontal 0°.
                    g.axis = glm::vec4(perpendicularTo(direction, l.up), 0.0f);
                }
                break;
            }
            case LightType::Directional: {
                type = GpuLightType::Sun;  // lux; lst:6 takes the disk's sin and cos
                g.params = glm::vec4(0.0f, 0.0f, std::sin(l.sunAngularRadius),
                                     std::cos(l.sunAngularRadius));
                break;
            }
            case LightType::Sphere:
            case LightType::Disk:
            case LightType::Rect:
            case LightType::Tube: {
                lighting::AreaLightShape shape;
                if (l.type == LightType::Rect) {
                    if (!(l.width > 0.0f && l.height > 0.0f))
                        return fail(ErrorCode::InvalidInput,
                                    label + ": width and height must be positive metres, got " +
                                        std::to_string(l.width) + " x " + std::to_string(l.height));
                    if (glm::length(glm::cross(l.up, direction)) < 1e-6f)
                        return fail(ErrorCode::InvalidInput,
                                    label +
                                        ": up is parallel to the direction (or zero); the rect "
                                        "needs a height axis");
                    shape = {lighting::AreaShape::Rectangle, 0.0, 0.0, l.width, l.height};
                    type = GpuLightType::Rect;
                    g.params = glm::vec4(0.0f, 0.0f, 0.0f, l.width);
                    g.axis = glm::vec4(perpendicularTo(direction, l.up), l.height);
                } else {
                    if (!(l.radius > 0.0f))
                        return fail(ErrorCode::InvalidInput,
                                    label + ": radius must be positive metres, got " +
                                        std::to_string(l.radius));
                    if (l.type == LightType::Tube && !(l.length > 0.0f))
                        return fail(ErrorCode::InvalidInput,
                                    label + ": length must be positive metres, got " +
                                        std::to_string(l.length));
                    shape.shape = l.type == LightType::Sphere ? lighting::AreaShape::Sphere
                                  : l.type == LightType::Disk ? lighting::AreaShape::Disk
                                                              : lighting::AreaShape::Tube;
                    shape.radius = l.radius;
                    shape.length = l.length;
                    type = l.type == LightType::Sphere ? GpuLightType::Sphere
                           : l.type == LightType::Disk ? GpuLightType::Disk
                                                       : GpuLightType::Tube;
                    // A disk's cone (lst:9): the spot's scale and offset, and in axis.w how far behind
                    // the disk its virtual apex lies (r / tan θ_outer); without one, scale 0, offset 1.
                    lighting::AngleScaleOffset cone;
                    if (l.type == LightType::Disk && l.cone) {
                        cone = lighting::spotAngleScaleOffset(l.innerAngle, l.outerAngle);
                        g.axis = glm::vec4(
                            0.0f, 0.0f, 0.0f,
                            l.radius / std::tan(std::clamp(l.outerAngle, 1e-3f, 1.5707f)));
                    }
                    g.params = glm::vec4(cone.scale, cone.offset, l.radius,
                                         l.type == LightType::Tube ? l.length : 0.0f);
                }
                const lighting::AreaUnit unit = l.unit == "lm"     ? lighting::AreaUnit::Lumens
                                                : l.unit == "nits" ? lighting::AreaUnit::Nits
                                                                   : lighting::AreaUnit::Ev100;
                value =
                    lighting::areaLightLuminance(shape, l.intensity, unit);  // tbl:12, eq:12: cd/m²
                break;
            }
        }
        g.positionType.w = static_cast<float>(type);
        const glm::vec3 rgb = color * static_cast<float>(value);
        g.intensity = glm::vec4(rgb, g.intensity.a);
        if (!std::isfinite(rgb.r) || !std::isfinite(rgb.g) || !std::isfinite(rgb.b))
            return fail(ErrorCode::InvalidInput, label + ": intensity " +
                                                     std::to_string(l.intensity) + " " + l.unit +
                                                     " is not a finite value on the GPU");
        table.lights.push_back(g);
    }
    return table;
}

}  // namespace rg::lighting

// scene.light, scene.environment, scene.lightmap and scene.probe -> the Scene's lights (each
// type's fields and units, seed 000 tbl:8), its environment, lightmap settings and probes.
#include <algorithm>
#include <map>

#include <glm/gtc/matrix_transform.hpp>

#include "core/light_units.h"
#include "lua/declarations.h"
#include "scene.h"
#include "scene_detail.h"
#include "scene_script_detail.h"

namespace rg {

using namespace scene_detail;

namespace scene_script {

Result<void> Builder::light(const Declaration& d) {
    Where w = where(d);
    const Value& b = d.body;
    if (auto r = checkFields(
            w, b, {"type",        "intensity",      "unit",      "color",   "temperature",
                   "locus",       "position",       "direction", "target",  "up",
                   "baked",       "radius",         "width",     "height",  "length",
                   "inner_angle", "outer_angle",    "range",     "ies",     "ies_mode",
                   "exact_cone",  "angular_radius", "shadow",    "visible", "doc"});
        !r)
        return r;
    Light l;
    l.name = d.name;
    if (!b.has("type"))
        return w.at("type").error(
            "missing (expected one of: 'point', 'spot', 'sun', 'sphere', 'disk', 'rect', 'tube')");
    std::string type;
    RG_TRY(type, choice(w, b, "type", "",
                        {"point", "spot", "sun", "directional", "sphere", "disk", "rect", "tube"},
                        "light type"));
    const std::map<std::string, LightType> types = {
        {"point", LightType::Point},     {"spot", LightType::Spot},
        {"sun", LightType::Directional}, {"directional", LightType::Directional},
        {"sphere", LightType::Sphere},   {"disk", LightType::Disk},
        {"rect", LightType::Rect},       {"tube", LightType::Tube}};
    l.type = types.at(type);
    const bool punctual = l.type == LightType::Point || l.type == LightType::Spot;
    const bool sun = l.type == LightType::Directional;
    const std::string a = "a " + type + " light";

    // Which fields this type has (seed 000 §4.4-4.7).
    auto only = [&](const char* field, bool allowed, const std::string& who) -> Result<void> {
        if (b.has(field) && !allowed)
            return w.at(field).error("not used by " + a + " (only by " + who + ")");
        return {};
    };
    if (auto r = only(
            "radius",
            l.type == LightType::Sphere || l.type == LightType::Disk || l.type == LightType::Tube,
            "sphere, disk and tube lights");
        !r)
        return r;
    if (auto r = only("width", l.type == LightType::Rect, "rect lights"); !r) return r;
    if (auto r = only("height", l.type == LightType::Rect, "rect lights"); !r) return r;
    if (auto r = only("up", l.type == LightType::Rect, "rect lights"); !r) return r;
    if (auto r = only("length", l.type == LightType::Tube, "tube lights"); !r) return r;
    if (auto r = only("inner_angle", l.type == LightType::Spot || l.type == LightType::Disk,
                      "spot and disk lights");
        !r)
        return r;
    if (auto r = only("outer_angle", l.type == LightType::Spot || l.type == LightType::Disk,
                      "spot and disk lights");
        !r)
        return r;
    if (l.type == LightType::Disk && b.has("inner_angle") && !b.has("outer_angle"))
        return w.at("inner_angle")
            .error("a disk's cone needs its outer_angle too (seed 000 lst:9)");
    if (auto r = only("ies", punctual, "point and spot lights"); !r) return r;
    if (auto r = only("ies_mode", punctual, "point and spot lights with an IES profile"); !r)
        return r;
    if (b.has("ies_mode") && !b.has("ies"))
        return w.at("ies_mode").error("needs an ies profile to apply");
    if (auto r = only("exact_cone", l.type == LightType::Spot, "spot lights"); !r) return r;
    if (auto r = only("angular_radius", sun, "the sun"); !r) return r;
    if (auto r = only("range", !sun, "local lights"); !r) return r;
    if (auto r = only("shadow", !sun,
                      "local lights; the sun's shadow is the pipeline's sun_shadows parameter");
        !r)
        return r;
    if (auto r = only("direction", l.type != LightType::Sphere, "lights with an orientation"); !r)
        return r;
    if (auto r = only("target", l.type != LightType::Sphere, "lights with an orientation"); !r)
        return r;

    // Units: seed 000 tbl:8.
    std::vector<std::string> units = punctual ? std::vector<std::string>{"lm", "cd"}
                                     : sun    ? std::vector<std::string>{"lux"}
                                              : std::vector<std::string>{"lm", "nits", "ev100"};
    RG_TRY(l.unit, string(w, b, "unit", units[0]));
    if (std::find(units.begin(), units.end(), l.unit) == units.end()) {
        const std::vector<std::string> all = {"lm", "cd", "lux", "nits", "ev100"};
        if (std::find(all.begin(), all.end(), l.unit) == all.end())
            return w.at("unit").error("unknown unit '" + l.unit + "'" + suggestion(l.unit, all) +
                                      "; " + a + " takes " + joinQuoted(units));
        return w.at("unit").error(a + " cannot be given in '" + l.unit +
                                  "' (seed 000 tbl:8); expected " + joinQuoted(units));
    }
    if (!b.has("intensity"))
        return w.at("intensity").error("missing (expected a number, in " + joinQuoted(units) + ")");
    RG_TRY(l.intensity, numberF(w, b, "intensity", 0.0f,
                                l.unit == "ev100" ? Range::any() : Range::nonNegative()));

    if (b.has("color") && b.has("temperature"))
        return w.at("temperature").error("give either color or temperature, not both");
    RG_TRY(l.color, colour(w, b, "color", l.color, Range::nonNegative()));
    // The ranges lights::colorTemperatureXy converts: the black body 1667–25000 K, daylight 4000–25000 K.
    std::string locus;
    RG_TRY(locus, choice(w, b, "locus", "blackbody", {"blackbody", "daylight"},
                         "colour temperature locus"));
    if (b.has("locus") && !b.has("temperature"))
        return w.at("locus").error("applies with a temperature only");
    l.daylight = locus == "daylight";
    RG_TRY(l.temperatureK, numberF(w, b, "temperature", 0.0f,
                                   Range::closed(l.daylight ? lights::kMinDaylightTemperature
                                                            : lights::kMinColorTemperature,
                                                 lights::kMaxColorTemperature)));

    RG_TRY(l.position, vec3(w, b, "position", l.position));
    if (b.has("direction") && b.has("target"))
        return w.at("target").error("give either direction or target, not both");
    if (b.has("direction")) {
        glm::vec3 dir;
        RG_TRY(dir, vec3(w, b, "direction", l.direction));
        if (glm::length(dir) < 1e-6f)
            return w.at("direction").error("expected a non-zero vector, got {0, 0, 0}");
        l.direction = glm::normalize(dir);
    } else if (b.has("target")) {
        glm::vec3 target;
        RG_TRY(target, vec3(w, b, "target", glm::vec3(0.0f)));
        if (glm::length(target - l.position) < 1e-6f)
            return w.at("target").error("equals position; the light needs a direction");
        l.direction = glm::normalize(target - l.position);
    } else if (l.type != LightType::Point && l.type != LightType::Sphere)
        return w.at("direction").error("missing (" + a + " needs direction or target)");

    auto need = [&](const char* field, float& out) -> Result<void> {
        if (!b.has(field))
            return w.at(field).error("missing (" + a + " needs its " + field + " in metres)");
        auto r = numberF(w, b, field, 0.0f, Range::positive());
        if (!r) return std::unexpected(r.error());
        out = *r;
        return {};
    };
    if (l.type == LightType::Sphere || l.type == LightType::Disk || l.type == LightType::Tube)
        if (auto r = need("radius", l.radius); !r) return r;
    if (l.type == LightType::Rect) {
        if (auto r = need("width", l.width); !r) return r;
        if (auto r = need("height", l.height); !r) return r;
        glm::vec3 up;
        RG_TRY(up, vec3(w, b, "up", l.up));
        if (glm::length(glm::cross(up, l.direction)) < 1e-6f)
            return w.at("up").error(
                "is parallel to the light's direction (or zero); the rect needs a height axis");
        l.up = glm::normalize(up);
    }
    if (l.type == LightType::Tube)
        if (auto r = need("length", l.length); !r) return r;
    if (l.type == LightType::Spot || (l.type == LightType::Disk && b.has("outer_angle"))) {
        l.cone = l.type == LightType::Disk;
        float inner = 0.0f, outer = 45.0f;
        RG_TRY(inner, numberF(w, b, "inner_angle", inner, Range::closed(0, 90)));
        RG_TRY(outer, numberF(w, b, "outer_angle", outer, Range::openLow(0, 90)));
        if (inner > outer)
            return w.at("inner_angle")
                .error("is " + formatNumber(inner) + "°, wider than outer_angle (" +
                       formatNumber(outer) + "°)");
        l.innerAngle = inner * kDegrees;
        l.outerAngle = outer * kDegrees;
    }
    RG_TRY(l.range, numberF(w, b, "range", 0.0f, Range::nonNegative()));
    if (b.has("ies")) RG_TRY(l.ies, existingFile(w, b, "ies"));
    if (b.has("ies_mode"))
        RG_TRY(l.iesMode, choice(w, b, "ies_mode", "", {"mask", "intensity"}, "IES mode"));
    RG_TRY(l.exactCone, boolean(w, b, "exact_cone", false));
    RG_TRY(l.castShadows, boolean(w, b, "shadow", false));
    RG_TRY(l.baked, boolean(w, b, "baked", false));
    if (auto r = only("visible", !punctual && !sun, "sphere, disk, rect and tube lights"); !r)
        return r;
    RG_TRY(l.visible, boolean(w, b, "visible", true));
    float angular = 0.2664f;
    RG_TRY(angular, numberF(w, b, "angular_radius", angular, Range::openLow(0, 10)));
    l.sunAngularRadius = angular * kDegrees;
    scene.lights.push_back(std::move(l));
    return {};
}

Result<void> Builder::environment(const Declaration& d) {
    Where w = where(d);
    const Value& b = d.body;
    if (auto r = checkFields(
            w, b,
            {"kind", "file", "color", "intensity", "unit", "rotation", "turbidity", "sun", "doc"});
        !r)
        return r;
    Environment e;
    e.name = d.name;
    if (!b.has("kind"))
        return w.at("kind").error("missing (expected one of: 'sky', 'hdr', 'color')");
    RG_TRY(e.kind, choice(w, b, "kind", "", {"sky", "hdr", "color"}, "environment kind"));
    if (b.has("file") && e.kind != "hdr")
        return w.at("file").error("applies to kind = \"hdr\" only");
    if (b.has("color") && e.kind != "color")
        return w.at("color").error("applies to kind = \"color\" only");
    if (b.has("turbidity") && e.kind != "sky")
        return w.at("turbidity").error("applies to kind = \"sky\" only");
    RG_TRY(e.turbidity, numberF(w, b, "turbidity", e.turbidity, Range::closed(1.7, 10)));
    if (b.has("sun") && e.kind != "hdr")
        return w.at("sun").error(
            "applies to kind = \"hdr\" only (a sky's sun is the scene's light)");
    RG_TRY(e.sun, choice(w, b, "sun", "auto", kEnvironmentSunModes, "environment sun"));
    if (e.kind == "hdr") {
        if (!b.has("file"))
            return w.at("file").error(
                "missing (expected an equirectangular .hdr or .exr, relative to the script)");
        RG_TRY(e.file, existingFile(w, b, "file"));
    }
    RG_TRY(e.color, colour(w, b, "color", e.color, Range::nonNegative()));
    RG_TRY(e.intensity, numberF(w, b, "intensity", e.intensity, Range::nonNegative()));
    RG_TRY(e.unit, string(w, b, "unit", "nits"));
    if (e.unit != "nits")
        return w.at("unit").error(
            "an environment's luminance is in 'nits' (seed 000 tbl:8), got '" + e.unit + "'");
    float rotation = 0.0f;
    RG_TRY(rotation, numberF(w, b, "rotation", rotation, Range::closed(-360, 360)));
    e.rotation = rotation * kDegrees;
    scene.environment = e;
    return {};
}

// scene.lightmap "name" { density, lobes, samples, bounces, max_size }
Result<void> Builder::lightmap(const Declaration& d) {
    Where w = where(d);
    const Value& b = d.body;
    if (auto r = checkFields(w, b, {"density", "lobes", "samples", "bounces", "max_size", "doc"});
        !r)
        return r;
    LightmapSettings s;
    s.name = d.name;
    s.origin = d.origin;
    RG_TRY(s.density, numberF(w, b, "density", s.density, Range::openLow(0, 1024)));
    double lobes = s.lobes;
    RG_TRY(lobes, number(w, b, "lobes", lobes, Range{1, 64, false, false, true}));
    if (lobes != 5 && lobes != 6 && lobes != 9 && lobes != 12)
        return w.at("lobes").error("expected 5, 6, 9 or 12 (seed 003 \"Light Map Data\"), got " +
                                   formatNumber(lobes));
    s.lobes = static_cast<int>(lobes);
    double samples = s.samples, bounces = s.bounces, maxSize = s.maxSize;
    RG_TRY(samples, number(w, b, "samples", samples, Range{1, 65536, false, false, true}));
    RG_TRY(bounces, number(w, b, "bounces", bounces, Range{1, 16, false, false, true}));
    RG_TRY(maxSize, number(w, b, "max_size", maxSize,
                           Range{64, 4096, false, false,
                                 true}));  // 4096² × 13 layers is ~1.7 GiB on the GPU
    s.samples = static_cast<int>(samples);
    s.bounces = static_cast<int>(bounces);
    s.maxSize = static_cast<int>(maxSize);
    scene.lightmap = s;
    return {};
}

// scene.probe "name" { position, shape = "sphere" (radius) | "box" (size, rotation), fade, priority }
Result<void> Builder::probe(const Declaration& d) {
    Where w = where(d);
    const Value& b = d.body;
    if (auto r = checkFields(w, b,
                             {"position", "shape", "radius", "size", "rotation", "influence",
                              "fade", "priority", "doc"});
        !r)
        return r;
    if (scene.probes.size() >= kMaxProbes)
        return w.error("a scene has at most " + std::to_string(kMaxProbes) +
                       " light probes (shaders/lib/probes.glsl RG_MAX_PROBES)");
    Probe p;
    p.name = d.name;
    p.origin = d.origin;
    std::string shape;
    RG_TRY(shape, choice(w, b, "shape", "sphere", {"sphere", "box"}, "probe shape"));
    p.box = shape == "box";
    if (p.box && b.has("radius"))
        return w.at("radius").error("a box probe has a size, not a radius");
    if (!p.box && (b.has("size") || b.has("rotation")))
        return w.at(b.has("size") ? "size" : "rotation")
            .error("a sphere probe has a radius (give shape = \"box\" for a size)");
    RG_TRY(p.position, vec3(w, b, "position", p.position));
    RG_TRY(p.radius, numberF(w, b, "radius", p.radius, Range::positive()));
    RG_TRY(p.size, vec3(w, b, "size", p.size, "{x, y, z} in metres", Range::positive()));
    glm::vec3 rotation(0.0f);
    RG_TRY(rotation, vec3(w, b, "rotation", rotation, "{x, y, z} in degrees"));
    p.rotation = glm::mat3(placement(glm::vec3(0.0f), rotation * kDegrees));
    if (b.has("influence")) {
        if (p.box)
            RG_TRY(p.influenceSize,
                   vec3(w, b, "influence", p.size, "{x, y, z} in metres (the box of influence)",
                        Range::positive()));
        else
            RG_TRY(p.influenceRadius, numberF(w, b, "influence", p.radius, Range::positive()));
    }
    RG_TRY(p.fade, numberF(w, b, "fade", p.fade, Range::nonNegative()));
    float priority = 0.0f;
    RG_TRY(priority, numberF(w, b, "priority", priority, Range{-1000, 1000, false, false, true}));
    p.priority = static_cast<int>(priority);
    scene.probes.push_back(p);
    return {};
}

}  // namespace scene_script

}  // namespace rg

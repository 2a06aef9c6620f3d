// scene.camera -> the Scene's cameras (perspective from fov or focal length, orthographic from
// height, exposure settings), and the default camera that frames a scene without one.
#include <algorithm>
#include <cmath>

#include "lua/declarations.h"
#include "scene.h"
#include "scene_detail.h"
#include "scene_script_detail.h"

namespace rg {

using namespace scene_detail;

namespace scene_script {

Result<void> Builder::camera(const Declaration& d) {
    Where w = where(d);
    const Value& b = d.body;
    if (auto r = checkFields(
            w, b,
            {"position", "target", "up", "fov", "focal_length", "sensor_height", "height",
             "aperture", "shutter", "iso", "ec", "near", "far", "path", "doc"});
        !r)
        return r;
    Camera c;
    c.name = d.name;
    c.position = glm::vec3(0.0f, 1.0f, 5.0f);
    RG_TRY(c.position, vec3(w, b, "position", c.position));
    RG_TRY(c.target, vec3(w, b, "target", c.target));
    RG_TRY(c.up, vec3(w, b, "up", c.up));
    if (glm::length(c.target - c.position) < 1e-6f)
        return w.at("target").error("equals position; the camera needs a direction to look in");
    if (glm::length(glm::cross(c.up, c.target - c.position)) <
        1e-6f * glm::length(c.target - c.position))
        return w.at("up").error(
            "is parallel to the view direction (or zero); e.g. up = {0, 0, -1} for a camera "
            "looking straight down");
    if (b.has("fov") && b.has("focal_length"))
        return w.at("focal_length")
            .error("give either fov or focal_length (with sensor_height), not both");
    if (b.has("sensor_height") && !b.has("focal_length"))
        return w.at("sensor_height").error("applies with focal_length only");
    float fovDeg = 45.0f;
    RG_TRY(fovDeg, numberF(w, b, "fov", fovDeg, Range::open(0, 180)));
    c.verticalFov = fovDeg * kDegrees;
    if (b.has("focal_length")) {
        float focalMm = 0.0f, sensorMm = 24.0f;
        RG_TRY(focalMm, numberF(w, b, "focal_length", focalMm, Range::positive()));
        RG_TRY(sensorMm, numberF(w, b, "sensor_height", sensorMm, Range::positive()));
        c.focalLength = focalMm / 1000.0f;
        c.sensorHeight = sensorMm / 1000.0f;
        c.verticalFov = 2.0f * std::atan(c.sensorHeight / (2.0f * c.focalLength));
    }
    // height = metres: an orthographic camera showing that much of the scene top to bottom.
    if (b.has("height")) {
        if (b.has("fov") || b.has("focal_length"))
            return w.at("height").error(
                "an orthographic camera (height) has no fov or focal_length");
        RG_TRY(c.orthoHeight, numberF(w, b, "height", c.orthoHeight, Range::positive()));
        c.orthographic = true;
    }
    RG_TRY(c.aperture, numberF(w, b, "aperture", c.aperture, Range::closed(0.5, 128)));
    RG_TRY(c.shutter, numberF(w, b, "shutter", c.shutter, Range::openLow(0, 60)));
    RG_TRY(c.iso, numberF(w, b, "iso", c.iso, Range::closed(1, 1000000)));
    RG_TRY(c.exposureCompensation,
           numberF(w, b, "ec", c.exposureCompensation, Range::closed(-20, 20)));
    RG_TRY(c.nearPlane, numberF(w, b, "near", c.nearPlane, Range::positive()));
    RG_TRY(c.farPlane, numberF(w, b, "far", c.farPlane, Range::positive()));
    if (c.farPlane <= c.nearPlane)
        return w.at("far").error("is " + formatNumber(c.farPlane) + ", not beyond near (" +
                                 formatNumber(c.nearPlane) + ")");
    // path = { { time = 0, position = {...}, target = {...} }, ... }: a camera move.
    if (b.has("path")) {
        const Value& path = b["path"];
        if (!path.isList() || path.asList().size() < 2)
            return w.at("path").error(
                "expected a list of at least two keys { time = s, position = {x, y, z}, target = "
                "{x, y, z} }, got " +
                describe(path));
        for (size_t i = 0; i < path.asList().size(); ++i) {
            const Where wk = w.at("path").index(i);
            const Value& key = path.asList()[i];
            if (!key.isTable())
                return wk.error(
                    "expected a key { time = s, position = {x, y, z}, target = {x, y, z} }");
            if (auto r = checkFields(wk, key, {"time", "position", "target"}); !r) return r;
            if (!key.has("time") || !key.has("position") || !key.has("target"))
                return wk.error("a key needs time, position and target");
            Camera::Key k;
            RG_TRY(k.time, numberF(wk, key, "time", 0.0f, Range::closed(0, 1e6)));
            RG_TRY(k.position, vec3(wk, key, "position", k.position));
            RG_TRY(k.target, vec3(wk, key, "target", k.target));
            if (!c.path.empty() && k.time <= c.path.back().time)
                return wk.at("time").error("is " + formatNumber(k.time) +
                                           ", not after the key before (" +
                                           formatNumber(c.path.back().time) + ")");
            if (glm::length(k.target - k.position) < 1e-6f)
                return wk.at("target").error("equals position; the camera needs a direction");
            c.path.push_back(k);
        }
    }
    scene.cameras.push_back(c);
    return {};
}

// A camera that sees the whole scene from the front, a little above.
void Builder::defaultCamera() {
    Camera c;
    c.name = "default";
    const glm::vec3 centre = (scene.boundsMin + scene.boundsMax) * 0.5f;
    const float radius = std::max(0.5f * glm::length(scene.boundsMax - scene.boundsMin), 0.5f);
    const float distance = radius / std::sin(c.verticalFov * 0.5f) * 1.05f;
    c.target = centre;
    c.position = centre + glm::normalize(glm::vec3(0.0f, 0.45f, 1.0f)) * distance;
    c.nearPlane = std::max(0.01f, (distance - radius) * 0.5f);
    c.farPlane = std::max(1000.0f, (distance + radius) * 2.0f);
    scene.cameras.push_back(c);
}

}  // namespace scene_script

Camera Camera::at(double seconds) const {
    if (path.empty()) return *this;
    Camera c = *this;
    const float t = static_cast<float>(seconds);
    c.position = pathCurve(path, t, &Key::position);
    c.target = pathCurve(path, t, &Key::target);
    return c;
}

glm::mat4 Node::at(double seconds) const {
    const glm::mat4 below =
        animation
            ? animationPlacement * animation->world(static_cast<size_t>(animationNode), seconds) *
                  animationLocal
            : placed;
    if (path.empty()) return animation ? below : world;
    const float t = static_cast<float>(seconds);
    return placement(pathCurve(path, t, &Key::position), pathCurve(path, t, &Key::rotation)) *
           below;
}

}  // namespace rg

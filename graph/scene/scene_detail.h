// Internal to rg_scene: what the glTF reader, the writer and the Lua scene builder share.
// Not a public header.
#pragma once

#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include "scene.h"

// `lhs = value of expr`, or return its error: several checks in a row in the loaders.
#define RG_TRY(lhs, expr)                                      \
    do {                                                       \
        auto rg_try_ = (expr);                                 \
        if (!rg_try_) return std::unexpected(rg_try_.error()); \
        lhs = std::move(*rg_try_);                             \
    } while (0)

namespace rg {
struct Scene;
}

namespace rg::scene_detail {

// translate(position) · Rz · Ry · Rx: a Lua scene's `position` and `rotation` (radians about X,
// then Y, then Z), as objects, decals, probes and paths place things.
inline glm::mat4 placement(glm::vec3 position, glm::vec3 radians) {
    glm::mat4 m = glm::translate(glm::mat4(1.0f), position);
    m = glm::rotate(m, radians.z, glm::vec3(0, 0, 1));
    m = glm::rotate(m, radians.y, glm::vec3(0, 1, 0));
    return glm::rotate(m, radians.x, glm::vec3(1, 0, 0));
}

// glTF's T · R · S (a node's translation, unit rotation quaternion and scale).
inline glm::mat4 trs(glm::vec3 t, glm::quat q, glm::vec3 s) {
    return glm::translate(glm::mat4(1.0f), t) * glm::mat4_cast(q) * glm::scale(glm::mat4(1.0f), s);
}

// A path's field at time t: through its keys (ascending `time`) on a cubic Hermite curve with
// Catmull-Rom tangents (per second, from the neighbouring keys; zero at the ends), held before the
// first key and after the last. A camera's and a node's paths.
template <typename Key>
glm::vec3 pathCurve(const std::vector<Key>& path, float t, glm::vec3 Key::*field) {
    if (t <= path.front().time || path.size() == 1) return path.front().*field;
    if (t >= path.back().time) return path.back().*field;
    size_t i = 0;
    while (path[i + 1].time < t) ++i;
    const Key &a = path[i], &b = path[i + 1];
    const float span = b.time - a.time, u = (t - a.time) / span;
    auto tangent = [&](size_t k) {
        if (k == 0 || k + 1 >= path.size()) return glm::vec3(0.0f);
        return (path[k + 1].*field - path[k - 1].*field) / (path[k + 1].time - path[k - 1].time);
    };
    const float u2 = u * u, u3 = u2 * u;
    return (2 * u3 - 3 * u2 + 1) * (a.*field) + (u3 - 2 * u2 + u) * span * tangent(i) +
           (-2 * u3 + 3 * u2) * (b.*field) + (u3 - u2) * span * tangent(i + 1);
}

// Decodes a PNG or JPEG held in memory into four float channels in [0, 1] (8-bit samples / 255,
// 16-bit / 65535), no colour conversion. The error message is the decoder's reason.
Result<Image> decodeImage(const unsigned char* data, size_t size);

// Encodes 1-4 channel values in [0, 1] as an 8-bit PNG (round(clamp(v) * 255)).
Result<std::vector<unsigned char>> encodePng(const Image& image);

// "'path'", how messages of this module name a file.
inline std::string quote(const std::string& path) { return "'" + path + "'"; }

// The OS's text for errno (thread-safe).
std::string errnoText(int err);

// The whole file, or NotFound/Io "cannot open 'path': reason" (`path` as given).
Result<std::vector<unsigned char>> readFile(const std::string& path);

// A material's texture file in scene.images, decoded once per file and encoding (`path` as
// given, the image's name; mips are the caller's): its index, or readFile's error, or "cannot
// decode 'path': reason".
Result<int32_t> textureFile(Scene& scene, const std::string& path, bool srgb);

}  // namespace rg::scene_detail

// glTF nodes -> Scene nodes, cameras and lights: the hierarchy walked once with its world
// transforms (cycles, shared children and depth refused), KHR_lights_punctual, rgraph's extras.
#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "gltf_load_detail.h"
#include "scene_detail.h"
#include "tinygltf.h"

namespace rg {

using namespace scene_detail;

namespace gltf_load {

namespace {

constexpr size_t kMaxDepth = 1000;  // node hierarchy levels (recursion depth)

}  // namespace

Result<glm::mat4> Loader::localTransform(size_t index) {
    const auto& n = model.nodes[index];
    const std::string where = named("node", index, n.name);
    if (!n.matrix.empty()) {
        if (n.matrix.size() != 16)
            return error(
                ErrorCode::InvalidInput,
                where + ": matrix has " + std::to_string(n.matrix.size()) + " values, expected 16");
        glm::mat4 m;
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r) {
                auto v = ranged(where + ": matrix[" + std::to_string(c * 4 + r) + "]",
                                n.matrix[size_t(c * 4 + r)], -1e30, 1e30);
                if (!v) return std::unexpected(v.error());
                m[c][r] = *v;  // column-major, as glm
            }
        return m;
    }
    auto sized = [&](const std::vector<double>& v, size_t want, const char* what) -> Result<void> {
        if (!v.empty() && v.size() != want)
            return error(ErrorCode::InvalidInput, where + ": " + what + " has " +
                                                      std::to_string(v.size()) +
                                                      " values, expected " + std::to_string(want));
        return {};
    };
    if (auto r = sized(n.translation, 3, "translation"); !r) return std::unexpected(r.error());
    if (auto r = sized(n.rotation, 4, "rotation"); !r) return std::unexpected(r.error());
    if (auto r = sized(n.scale, 3, "scale"); !r) return std::unexpected(r.error());
    glm::vec3 t, s;
    RG_TRY(t, ranged3(where + ": translation", n.translation, glm::vec3(0.0f), -1e30, 1e30));
    RG_TRY(s, ranged3(where + ": scale", n.scale, glm::vec3(1.0f), -1e30, 1e30));
    glm::quat q(1.0f, 0.0f, 0.0f, 0.0f);  // glm::quat(w, x, y, z); glTF stores x, y, z, w
    if (n.rotation.size() == 4) {
        glm::vec4 r;
        for (int k = 0; k < 4; ++k)
            RG_TRY(r[k], ranged(where + ": rotation[" + std::to_string(k) + "]",
                                n.rotation[size_t(k)], -1, 1));
        if (glm::length(r) < 1e-6f)
            return error(ErrorCode::InvalidInput,
                         where + ": rotation is not a unit quaternion (it is zero)");
        q = glm::normalize(glm::quat(r.w, r.x, r.y, r.z));
    }
    return scene_detail::trs(t, q, s);
}

Result<void> Loader::camera(size_t nodeIndex, const glm::mat4& world) {
    const auto& n = model.nodes[nodeIndex];
    if (size_t(n.camera) >= model.cameras.size())
        return error(ErrorCode::InvalidInput, named("node", nodeIndex, n.name) + ": camera " +
                                                  std::to_string(n.camera) + " does not exist");
    const auto& c = model.cameras[size_t(n.camera)];
    Camera cam;
    cam.name = !c.name.empty()   ? c.name
               : !n.name.empty() ? n.name
                                 : "camera " + std::to_string(n.camera);
    const std::string where = named("camera", size_t(n.camera), c.name);
    if (c.type == "orthographic") {
        // glTF: xmag, ymag are half the view's width and height in metres; rgraph keeps the
        // height and takes the width from the image's aspect.
        float ymag = 1.0f;
        RG_TRY(ymag, ranged(where + ": ymag", c.orthographic.ymag, 1e-9, 1e30));
        cam.orthographic = true;
        cam.orthoHeight = 2.0f * ymag;
        RG_TRY(cam.nearPlane, ranged(where + ": znear", c.orthographic.znear, 0, 1e30));
        cam.nearPlane = std::max(cam.nearPlane, 1e-4f);
        RG_TRY(cam.farPlane,
               ranged(where + ": zfar", c.orthographic.zfar, c.orthographic.znear, 1e30));
        if (cam.farPlane <= cam.nearPlane)
            return error(ErrorCode::InvalidInput, where + ": zfar must lie beyond znear");
    } else if (c.type == "perspective") {
        RG_TRY(cam.verticalFov, ranged(where + ": yfov", c.perspective.yfov, 1e-6, 3.14159));
        RG_TRY(cam.nearPlane, ranged(where + ": znear", c.perspective.znear, 1e-9, 1e30));
        // glTF: no zfar means an infinite projection; we keep the finite default.
        if (c.perspective.zfar > 0)
            RG_TRY(cam.farPlane,
                   ranged(where + ": zfar", c.perspective.zfar, c.perspective.znear, 1e30));
    } else {
        return error(ErrorCode::InvalidInput, where + ": unknown camera type '" + c.type +
                                                  "' (glTF has 'perspective' and 'orthographic')");
    }
    cam.position = glm::vec3(world[3]);
    cam.target = cam.position + glm::normalize(glm::vec3(world * glm::vec4(0, 0, -1, 0)));
    cam.up = glm::normalize(glm::vec3(world * glm::vec4(0, 1, 0, 0)));
    if (c.extras.IsObject() && c.extras.Get("rgraph").IsObject()) {
        const auto& x = c.extras.Get("rgraph");
        cam.aperture = float(number(x.Get("aperture"), cam.aperture));
        cam.shutter = float(number(x.Get("shutter"), cam.shutter));
        cam.iso = float(number(x.Get("iso"), cam.iso));
        cam.exposureCompensation = float(number(x.Get("ec"), cam.exposureCompensation));
        cam.focalLength = float(number(x.Get("focal_length"), cam.focalLength));
        cam.sensorHeight = float(number(x.Get("sensor_height"), cam.sensorHeight));
        // The exact target and up the scene had (the node only gives a direction).
        cam.target = vec3Of(x.Get("target"), cam.target);
        cam.up = vec3Of(x.Get("up"), cam.up);
    }
    scene.cameras.push_back(cam);
    return {};
}

Result<void> Loader::light(size_t nodeIndex, const glm::mat4& world) {
    const auto& n = model.nodes[nodeIndex];
    auto ext = n.extensions.find("KHR_lights_punctual");
    if (ext == n.extensions.end() || !ext->second.IsObject() || !ext->second.Has("light"))
        return {};
    const int li = indexOf(ext->second.Get("light"));
    if (li < 0 || size_t(li) >= model.lights.size())
        return error(ErrorCode::InvalidInput,
                     named("node", nodeIndex, n.name) + ": KHR_lights_punctual light " +
                         (li < 0 ? "index is not a whole number >= 0"
                                 : std::to_string(li) + " does not exist (" +
                                       std::to_string(model.lights.size()) + " lights)"));
    const auto& l = model.lights[size_t(li)];
    Light out;
    out.name = !l.name.empty() ? l.name : !n.name.empty() ? n.name : "light " + std::to_string(li);
    // KHR_lights_punctual: point and spot in candela, directional in lux.
    if (l.type == "point")
        out.type = LightType::Point, out.unit = "cd";
    else if (l.type == "spot")
        out.type = LightType::Spot, out.unit = "cd";
    else if (l.type == "directional")
        out.type = LightType::Directional, out.unit = "lux";
    else
        return error(ErrorCode::InvalidInput, named("light", size_t(li), l.name) + ": type '" +
                                                  l.type +
                                                  "', expected point, spot or directional");
    const std::string where = named("light", size_t(li), l.name);
    RG_TRY(out.color, ranged3(where + ": color", l.color, glm::vec3(1.0f), 0, 1));
    RG_TRY(out.intensity, ranged(where + ": intensity", l.intensity, 0, HUGE_VAL));
    RG_TRY(out.range, ranged(where + ": range", l.range, 0, HUGE_VAL));
    if (out.type == LightType::Spot) {
        RG_TRY(out.outerAngle,
               ranged(where + ": spot.outerConeAngle", l.spot.outerConeAngle, 0, 1.5707964));
        RG_TRY(out.innerAngle, ranged(where + ": spot.innerConeAngle", l.spot.innerConeAngle, 0,
                                      l.spot.outerConeAngle));
    }
    out.position = glm::vec3(world[3]);
    out.direction = glm::normalize(glm::vec3(world * glm::vec4(0, 0, -1, 0)));
    if (l.extras.IsObject() && l.extras.Get("rgraph").IsObject()) {
        const auto& x = l.extras.Get("rgraph");
        out.temperatureK = float(number(x.Get("temperature"), 0.0));
        if (x.Get("ies").IsString()) {
            auto file = extrasFile(x.Get("ies").Get<std::string>(), where + ": extras.rgraph.ies");
            if (!file) return std::unexpected(file.error());
            out.ies = *file;
        }
        if (x.Get("ies_mode").IsString()) {
            out.iesMode = x.Get("ies_mode").Get<std::string>();
            if (out.iesMode != "mask" && out.iesMode != "intensity")
                return fail(ErrorCode::InvalidInput, where + ": extras.rgraph.ies_mode '" +
                                                         out.iesMode +
                                                         "' is not 'mask' or 'intensity'");
        }
        if (x.Get("exact_cone").IsBool()) out.exactCone = x.Get("exact_cone").Get<bool>();
        if (x.Get("shadow").IsBool())
            out.castShadows = x.Get("shadow").Get<bool>() && out.type != LightType::Directional;
        out.sunAngularRadius = float(number(x.Get("angular_radius"), out.sunAngularRadius));
        // Written by exportGlb for a light declared in lumens (its cd is what rgraph renders).
        if (x.Get("lumens").IsNumber() &&
            (out.type == LightType::Point || out.type == LightType::Spot)) {
            RG_TRY(out.intensity, ranged(where + ": extras.rgraph.lumens",
                                         number(x.Get("lumens"), 0.0), 0, HUGE_VAL));
            out.unit = "lm";
        }
    }
    scene.lights.push_back(out);
    return {};
}

// EXT_mesh_gpu_instancing: the node's mesh once per instance, each at the node's transform times
// the instance's TRANSLATION, ROTATION (a unit quaternion, x y z w) and SCALE (each optional, all
// of one count), as a node of its own named "NAME #i".
Result<void> Loader::instances(size_t index, const std::string& name, const glm::mat4& world,
                               int32_t mesh) {
    const auto& n = model.nodes[index];
    const std::string where = named("node", index, n.name) + ": EXT_mesh_gpu_instancing";
    const tinygltf::Value& attributes =
        n.extensions.at("EXT_mesh_gpu_instancing").Get("attributes");
    if (!attributes.IsObject())
        return error(ErrorCode::InvalidInput, where + ".attributes: expected an object");
    struct Attribute {
        const char* semantic;
        int type;
        std::vector<float> values;
    } attrs[] = {{"TRANSLATION", TINYGLTF_TYPE_VEC3, {}},
                 {"ROTATION", TINYGLTF_TYPE_VEC4, {}},
                 {"SCALE", TINYGLTF_TYPE_VEC3, {}}};
    size_t count = 0;
    bool any = false;
    for (Attribute& a : attrs) {
        if (!attributes.Has(a.semantic)) continue;
        const int accessorIndex = indexOf(attributes.Get(a.semantic));
        auto values = readFloats(where, a.semantic, accessorIndex, a.type);
        if (!values) return std::unexpected(values.error());
        const size_t c = values->size() / (a.type == TINYGLTF_TYPE_VEC4 ? 4 : 3);
        if (any && c != count)
            return error(ErrorCode::InvalidInput,
                         where + ": " + a.semantic + " has " + std::to_string(c) +
                             " instances, the attributes before it " + std::to_string(count));
        count = c;
        any = true;
        a.values = std::move(*values);
    }
    if (!any)
        return error(ErrorCode::InvalidInput,
                     where + ".attributes: none of TRANSLATION, ROTATION, SCALE");
    if (count > kMaxInstances)
        return error(ErrorCode::InvalidInput, where + ": " + std::to_string(count) +
                                                  " instances (at most " +
                                                  std::to_string(kMaxInstances) + ")");
    for (size_t i = 0; i < count; ++i) {
        glm::vec3 t(0.0f), s(1.0f);
        glm::quat q(1.0f, 0.0f, 0.0f, 0.0f);
        if (!attrs[0].values.empty()) t = glm::make_vec3(&attrs[0].values[3 * i]);
        if (!attrs[1].values.empty()) {
            const float* r = &attrs[1].values[4 * i];
            q = glm::normalize(glm::quat(r[3], r[0], r[1], r[2]));
        }
        if (!attrs[2].values.empty()) s = glm::make_vec3(&attrs[2].values[3 * i]);
        const glm::mat4 local = scene_detail::trs(t, q, s);
        scene.nodes.push_back({name + " #" + std::to_string(i), world * local, mesh});
        nodeSources.emplace_back(index, local);
    }
    return {};
}

// Each node once: glTF nodes have at most one parent, and a node reached twice (a shared
// child, a cycle) would repeat or never end. Depth first with a stack of its own (not the
// call stack: a hostile hierarchy thousands deep must not overflow it).
Result<void> Loader::enter(size_t index, const glm::mat4& parent, std::vector<bool>& onPath,
                           std::vector<bool>& seen, size_t depth, glm::mat4& world) {
    if (onPath[index])
        return error(ErrorCode::InvalidInput,
                     named("node", index, model.nodes[index].name) +
                         " is its own ancestor (the node hierarchy has a cycle)");
    if (seen[index])
        return error(ErrorCode::InvalidInput,
                     named("node", index, model.nodes[index].name) +
                         " appears twice in the hierarchy (a glTF node has one parent)");
    if (depth > kMaxDepth)
        return error(ErrorCode::InvalidInput,
                     "the node hierarchy is deeper than " + std::to_string(kMaxDepth) + " levels");
    onPath[index] = seen[index] = true;
    const auto& n = model.nodes[index];
    auto local = localTransform(index);
    if (!local) return std::unexpected(local.error());
    world = parent * *local;
    worlds[index] = world;
    if (n.mesh >= 0) {
        if (size_t(n.mesh) >= model.meshes.size())  // not scene.meshes: it also holds copies
            return error(ErrorCode::InvalidInput, named("node", index, n.name) + ": mesh " +
                                                      std::to_string(n.mesh) + " does not exist (" +
                                                      std::to_string(model.meshes.size()) +
                                                      " meshes)");
        const std::string name = n.name.empty() ? scene.meshes[size_t(n.mesh)].name : n.name;
        int32_t mesh = n.mesh;
        RG_TRY(mesh, nodeMesh(index));
        if (auto it = n.extensions.find("EXT_mesh_gpu_instancing"); it != n.extensions.end()) {
            if (n.skin >= 0)
                warn(named("node", index, n.name) +
                     ": a skin on an instanced node is not applied (its instances are placed as "
                     "given)");
            if (auto r = instances(index, name, world, mesh); !r) return r;
        } else {
            if (n.skin >= 0) skinned.push_back({index, scene.nodes.size()});
            scene.nodes.push_back({name, world, mesh});
            nodeSources.emplace_back(index, glm::mat4(1.0f));
        }
    }
    if (n.camera >= 0)
        if (auto r = camera(index, world); !r) return r;
    return light(index, world);
}
Result<void> Loader::visit(size_t root, const glm::mat4& parent, std::vector<bool>& onPath,
                           std::vector<bool>& seen, size_t depth) {
    struct Frame {
        size_t index;
        glm::mat4 world;
        size_t next;
    };
    std::vector<Frame> stack;
    glm::mat4 world;
    walkParent[root] = -1;
    if (auto r = enter(root, parent, onPath, seen, depth, world); !r) return r;
    stack.push_back({root, world, 0});
    while (!stack.empty()) {
        Frame& f = stack.back();
        const auto& n = model.nodes[f.index];
        if (f.next == n.children.size()) {
            onPath[f.index] = false;
            stack.pop_back();
            continue;
        }
        const int child = n.children[f.next++];
        if (child < 0 || size_t(child) >= model.nodes.size())
            return error(ErrorCode::InvalidInput,
                         named("node", f.index, n.name) + ": child " + std::to_string(child) +
                             " does not exist (" + std::to_string(model.nodes.size()) + " nodes)");
        const glm::mat4 parentWorld = f.world;
        walkParent[size_t(child)] = int32_t(f.index);
        if (auto r = enter(size_t(child), parentWorld, onPath, seen, depth + stack.size(), world);
            !r)
            return r;
        stack.push_back({size_t(child), world, 0});
    }
    return {};
}

// exportGlb keeps a scene's environment in the glTF scene's extras.
Result<void> Loader::environment(const tinygltf::Value& extras) {
    if (!extras.IsObject() || !extras.Get("rgraph").IsObject() ||
        !extras.Get("rgraph").Get("environment").IsObject())
        return {};
    const auto& x = extras.Get("rgraph").Get("environment");
    Environment e;
    auto str = [&](const char* k, const std::string& def) {
        return x.Get(k).IsString() ? x.Get(k).Get<std::string>() : def;
    };
    e.name = str("name", e.name);
    e.kind = str("kind", e.kind);
    if (x.Get("file").IsString()) {
        auto file =
            extrasFile(x.Get("file").Get<std::string>(), "scene extras.rgraph.environment.file");
        if (!file) return std::unexpected(file.error());
        e.file = *file;
    }
    e.unit = str("unit", e.unit);
    e.color = vec3Of(x.Get("color"), e.color);
    e.intensity = float(number(x.Get("intensity"), e.intensity));
    e.rotation = float(number(x.Get("rotation"), e.rotation));
    e.turbidity = std::clamp(float(number(x.Get("turbidity"), e.turbidity)), 1.7f, 10.0f);
    e.sun = str("sun", e.sun);
    if (std::find(kEnvironmentSunModes.begin(), kEnvironmentSunModes.end(), e.sun) ==
        kEnvironmentSunModes.end())
        return fail(ErrorCode::InvalidInput,
                    "scene extras.rgraph.environment.sun: expected 'auto', 'light', 'remove' or "
                    "'keep', got '" +
                        e.sun + "'");
    scene.environment = e;
    return {};
}

Result<void> Loader::nodes() {
    std::vector<int> roots;
    if (!model.scenes.empty()) {
        const size_t s = model.defaultScene >= 0 && size_t(model.defaultScene) < model.scenes.size()
                             ? size_t(model.defaultScene)
                             : 0;
        roots = model.scenes[s].nodes;
        if (auto r = environment(model.scenes[s].extras); !r) return r;
    } else {
        std::vector<bool> child(model.nodes.size(), false);
        for (const auto& n : model.nodes)
            for (int c : n.children)
                if (c >= 0 && size_t(c) < child.size()) child[size_t(c)] = true;
        for (size_t i = 0; i < model.nodes.size(); ++i)
            if (!child[i]) roots.push_back(int(i));
    }
    std::vector<bool> onPath(model.nodes.size(), false), seen(model.nodes.size(), false);
    worlds.assign(model.nodes.size(), std::nullopt);
    walkParent.assign(model.nodes.size(), -2);
    for (int r : roots) {
        if (r < 0 || size_t(r) >= model.nodes.size())
            return error(ErrorCode::InvalidInput,
                         "scene root node " + std::to_string(r) + " does not exist (" +
                             std::to_string(model.nodes.size()) + " nodes)");
        if (auto v = visit(size_t(r), glm::mat4(1.0f), onPath, seen, 0); !v) return v;
    }
    return skins();
}

}  // namespace gltf_load

}  // namespace rg

#include "light_shapes.h"

#include <cmath>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "lighting/light_table.h"

namespace rg {

namespace {

// A frame whose +Y is `axis` (unit) and whose +Z lies along `up` made perpendicular to it.
glm::mat4 frameAlong(glm::vec3 position, glm::vec3 axis, glm::vec3 up) {
    glm::vec3 y = glm::normalize(axis);
    glm::vec3 z = up - y * glm::dot(up, y);
    if (glm::length(z) < 1e-4f) {
        const glm::vec3 other = std::abs(y.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 0, 1);
        z = other - y * glm::dot(other, y);
    }
    z = glm::normalize(z);
    const glm::vec3 x = glm::cross(y, z);
    glm::mat4 m(1.0f);
    m[0] = glm::vec4(x, 0.0f);
    m[1] = glm::vec4(y, 0.0f);
    m[2] = glm::vec4(z, 0.0f);
    m[3] = glm::vec4(position, 1.0f);
    return m;
}

}  // namespace

Result<size_t> addLightShapes(Scene& scene, const Value& standardParams) {
    size_t added = 0;
    const size_t lights = scene.lights.size();
    for (size_t i = 0; i < lights; ++i) {
        const Light l = scene.lights[i];  // a copy: the vectors below grow
        const bool area = l.type == LightType::Sphere || l.type == LightType::Disk ||
                          l.type == LightType::Rect || l.type == LightType::Tube;
        if (!area || !l.visible) continue;
        // The luminance the lighting uses, from the same conversion.
        auto table = lighting::convertLights({l});
        if (!table) return std::unexpected(table.error());
        if (table->lights.empty()) continue;
        const glm::vec3 nits(table->lights[0].intensity);

        Material m;
        m.name = l.name + " shape";
        m.model = "standard";
        m.baseColor = glm::vec3(0.0f);
        m.metalMask = 0.0f;
        m.reflectance = 0.0f;  // f0 = 0.16 · 0² and f90 = saturate(50 f0): no specular at all
        m.smoothness = 0.0f;
        m.emissive = nits;
        m.extra = standardParams;
        m.origin = "light '" + l.name + "'s shape";
        const uint32_t material = static_cast<uint32_t>(scene.materials.size());
        scene.materials.push_back(m);

        Mesh mesh;
        mesh.name = m.name;
        glm::mat4 world(1.0f);
        switch (l.type) {
            case LightType::Sphere:
                mesh.primitives.push_back(makeSphere(l.radius, 32, material));
                world = glm::translate(glm::mat4(1.0f), l.position);
                break;
            case LightType::Disk:
                mesh.primitives.push_back(makeDisk(l.radius, 48, material));
                world = frameAlong(l.position, l.direction, l.up);
                break;
            case LightType::Rect:
                // makePlane: width along X, depth along Z; the frame's Z is the rect's up.
                mesh.primitives.push_back(makePlane(l.width, l.height, material));
                world = frameAlong(l.position, l.direction, l.up);
                break;
            default:  // tube: the capsule around its axis
                mesh.primitives.push_back(makeCapsule(l.radius, l.length, 32, material));
                world = frameAlong(l.position, l.direction, l.up);
                break;
        }
        const int32_t meshIndex = static_cast<int32_t>(scene.meshes.size());
        scene.meshes.push_back(std::move(mesh));
        Node node;
        node.name = m.name;
        node.world = world;
        node.mesh = meshIndex;
        node.castShadows = false;
        node.lightShape = true;
        scene.nodes.push_back(node);
        ++added;
    }
    if (added) computeBounds(scene);
    return added;
}

}  // namespace rg

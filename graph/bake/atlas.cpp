// The lightmap atlas: one square per node, shelf-packed.
#include <algorithm>
#include <cmath>
#include <numeric>

#include "bake/lightmap.h"

namespace rg::bake {

namespace {

double worldArea(const Scene& scene, const Node& node) {
    double area = 0.0;
    for (const auto& p : scene.meshes[size_t(node.mesh)].primitives)
        for (size_t t = 0; t + 2 < p.indices.size(); t += 3) {
            glm::vec3 c[3];
            for (int k = 0; k < 3; ++k)
                c[k] = glm::vec3(node.world *
                                 glm::vec4(p.vertices.at(p.indices[t + size_t(k)]).position, 1.0f));
            area += 0.5 * double(glm::length(glm::cross(c[1] - c[0], c[2] - c[0])));
        }
    return area;
}

}  // namespace

Result<LightmapAtlas> packLightmap(const Scene& scene, const LightmapSettings& settings) {
    std::vector<size_t> nodes;
    std::vector<double> areas;
    for (size_t i = 0; i < scene.nodes.size(); ++i) {
        const Node& n = scene.nodes[i];
        if (n.mesh < 0 || size_t(n.mesh) >= scene.meshes.size()) continue;
        const Mesh& mesh = scene.meshes[size_t(n.mesh)];
        // Baked light belongs to where a surface stands: a node that moves would carry the light
        // of its first pose along (and its baked shadow would stay behind).
        if (n.dynamic)
            return fail(ErrorCode::InvalidInput,
                        "lightmap '" + settings.name + "': node '" + n.name +
                            "' moves (a path, a glTF animation or a dynamic mesh): a lightmapped "
                            "scene's nodes stand still; take the lightmap or the move away (a "
                            "glTF file's: scene.gltf's animation = \"none\")");
        for (const auto& p : mesh.primitives)
            if (!p.lightmapUv)
                return fail(
                    ErrorCode::InvalidInput,
                    "lightmap '" + settings.name + "': node '" + n.name + "' (mesh '" + mesh.name +
                        "') has no lightmap uvs: give its glTF primitives a TEXCOORD_1 set of "
                        "non-overlapping charts in [0, 1] (the scene's own shapes have them)");
        nodes.push_back(i);
        areas.push_back(worldArea(scene, n));
    }
    LightmapAtlas atlas;
    atlas.rects.assign(scene.nodes.size(), glm::vec4(0.0f));
    atlas.texelRects.assign(scene.nodes.size(), glm::uvec4(0u));
    if (nodes.empty()) return atlas;
    const uint32_t maxSize = static_cast<uint32_t>(std::max(settings.maxSize, 64));
    float density = settings.density;
    for (int attempt = 0; attempt < 64; ++attempt, density *= 0.85f) {
        std::vector<uint32_t> side(nodes.size());
        double total = 0.0;
        for (size_t k = 0; k < nodes.size(); ++k) {
            const double s = std::ceil(std::sqrt(areas[k]) * double(density));
            side[k] = static_cast<uint32_t>(
                std::clamp(s, double(kMinBoxLightmapTexels), double(maxSize - 2)));
            total += double(side[k] + 2) * double(side[k] + 2);
        }
        // Tallest first, left to right along shelves of the atlas's width.
        std::vector<size_t> order(nodes.size());
        std::iota(order.begin(), order.end(), size_t(0));
        std::stable_sort(order.begin(), order.end(),
                         [&](size_t a, size_t b) { return side[a] > side[b]; });
        uint32_t width = std::max<uint32_t>(
            side[order[0]] + 2, static_cast<uint32_t>(std::ceil(std::sqrt(total * 1.15))));
        width = (width + 3u) & ~3u;
        if (width > maxSize) continue;
        uint32_t x = 0, y = 0, shelf = 0;
        std::vector<glm::uvec2> at(nodes.size());
        for (size_t k : order) {
            const uint32_t s = side[k] + 2;
            if (x + s > width) x = 0, y += shelf, shelf = 0;
            at[k] = glm::uvec2(x, y);
            x += s;
            shelf = std::max(shelf, s);
        }
        const uint32_t height = (y + shelf + 3u) & ~3u;
        if (height > maxSize) continue;
        atlas.width = width;
        atlas.height = height;
        atlas.density = density;
        for (size_t k = 0; k < nodes.size(); ++k) {
            const glm::uvec2 inner = at[k] + 1u;
            atlas.texelRects[nodes[k]] = glm::uvec4(inner, side[k], 0u);
            atlas.rects[nodes[k]] =
                glm::vec4(float(side[k]) / float(width), float(side[k]) / float(height),
                          float(inner.x) / float(width), float(inner.y) / float(height));
        }
        return atlas;
    }
    return fail(ErrorCode::InvalidInput,
                "lightmap '" + settings.name + "': the scene's " + std::to_string(nodes.size()) +
                    " objects do not fit a " + std::to_string(maxSize) + "² atlas; raise max_size");
}

void applyAtlas(Scene& scene, const LightmapAtlas& atlas) {
    for (size_t i = 0; i < scene.nodes.size() && i < atlas.rects.size(); ++i)
        scene.nodes[i].lightmapRect = atlas.rects[i];
}

}  // namespace rg::bake

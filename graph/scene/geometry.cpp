// Generated geometry: tangent frames, flat normals, the Lua scene's primitives, bounds.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <unordered_map>
#include <vector>

#include "scene.h"

namespace rg {

const char* lightTypeName(LightType t) {
    switch (t) {
        case LightType::Point:
            return "point";
        case LightType::Spot:
            return "spot";
        case LightType::Directional:
            return "sun";
        case LightType::Sphere:
            return "sphere";
        case LightType::Disk:
            return "disk";
        case LightType::Rect:
            return "rect";
        case LightType::Tube:
            return "tube";
    }
    return "?";
}

namespace {

// Any unit vector perpendicular to n (n unit length).
glm::vec3 anyPerpendicular(const glm::vec3& n) {
    const glm::vec3 a = std::fabs(n.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
    return glm::normalize(glm::cross(n, a));
}

glm::vec3 safeNormalize(const glm::vec3& v, const glm::vec3& fallback) {
    const float len = glm::length(v);
    return len > 1e-20f && std::isfinite(len) ? v / len : fallback;
}

}  // namespace

// Tangents by the MikkTSpace algorithm (M. Mikkelsen, "Simulation of Wrinkled Surfaces Revisited",
// 2008), which glTF 2.0 §3.7.2.1 names for a normal-mapped mesh without TANGENT: the frame baked
// normal maps assume. Per triangle, dP/du and the sign of its uv area; at each corner that dP/du
// projected into the plane of the corner's normal and made unit, weighted by the corner's angle in
// that plane; summed over the corners whose vertices share position, normal and uv (identical
// vertices are one, as the algorithm welds them) and the triangle's uv orientation, so a vertex
// between mirrored uv halves becomes two. Not kept from it: the tangents' magnitudes (glTF's are
// unit) and its finer grouping of corners by how far their tangents diverge.
std::vector<uint32_t> generateTangents(Primitive& p, uint32_t uvSlot) {
    const size_t n = p.vertices.size();
    auto uvOf = [&](const Vertex& v) { return uvSlot == 1 ? v.uv1 : v.uv0; };
    // Identical vertices (position, normal, the slot's uv) share one sum: the first of them.
    std::vector<uint32_t> weld(n);
    {
        struct Key {
            float f[8];
            bool operator==(const Key& o) const { return std::memcmp(f, o.f, sizeof f) == 0; }
        };
        struct Hash {
            size_t operator()(const Key& k) const {
                uint64_t h = 1469598103934665603ull;  // FNV-1a over the words
                for (float x : k.f) {
                    uint32_t b = 0;
                    std::memcpy(&b, &x, 4);
                    h = (h ^ b) * 1099511628211ull;
                }
                return static_cast<size_t>(h);
            }
        };
        std::unordered_map<Key, uint32_t, Hash> first;
        first.reserve(n);
        for (size_t i = 0; i < n; ++i) {
            const Vertex& v = p.vertices[i];
            const glm::vec2 uv = uvOf(v);
            const Key k{{v.position.x, v.position.y, v.position.z, v.normal.x, v.normal.y,
                         v.normal.z, uv.x, uv.y}};
            weld[i] = first.emplace(k, static_cast<uint32_t>(i)).first->second;
        }
    }
    // Per welded vertex and side — 0: the triangle's uv area is negative (glTF's usual, v growing
    // downwards: w = +1), 1: positive (a mirrored half: w = −1) — the angle-weighted sum.
    std::vector<glm::vec3> sum(2 * n, glm::vec3(0.0f));
    std::vector<uint8_t> cornerSide(p.indices.size(), 0), cornerValid(p.indices.size(), 0);
    for (size_t t = 0; t + 2 < p.indices.size(); t += 3) {
        const uint32_t idx[3] = {p.indices[t], p.indices[t + 1], p.indices[t + 2]};
        if (idx[0] >= n || idx[1] >= n || idx[2] >= n) continue;
        const Vertex* v[3] = {&p.vertices[idx[0]], &p.vertices[idx[1]], &p.vertices[idx[2]]};
        const glm::vec3 e1 = v[1]->position - v[0]->position, e2 = v[2]->position - v[0]->position;
        const glm::vec2 d1 = uvOf(*v[1]) - uvOf(*v[0]), d2 = uvOf(*v[2]) - uvOf(*v[0]);
        const float det = d1.x * d2.y - d2.x * d1.y;
        if (std::fabs(det) < 1e-20f || !std::isfinite(det)) continue;  // no uv gradient
        const glm::vec3 dPdu = (e1 * d2.y - e2 * d1.y) / det;
        const uint8_t side = det > 0.0f ? 1 : 0;
        for (int k = 0; k < 3; ++k) {
            const glm::vec3 nrm = safeNormalize(v[k]->normal, glm::vec3(0, 0, 1));
            auto inPlane = [&](const glm::vec3& e) { return e - nrm * glm::dot(nrm, e); };
            const glm::vec3 os = inPlane(dPdu);
            const float len = glm::length(os);
            if (!(len > 1e-20f) || !std::isfinite(len)) continue;
            // The corner's angle between its two edges, both in the normal's plane.
            const glm::vec3 a = safeNormalize(inPlane(v[(k + 1) % 3]->position - v[k]->position),
                                              glm::vec3(0.0f)),
                            b = safeNormalize(inPlane(v[(k + 2) % 3]->position - v[k]->position),
                                              glm::vec3(0.0f));
            const float angle = std::acos(std::clamp(glm::dot(a, b), -1.0f, 1.0f));
            sum[2 * size_t(weld[idx[k]]) + side] += angle * (os / len);
            cornerSide[t + size_t(k)] = side;
            cornerValid[t + size_t(k)] = 1;
        }
    }
    // Each vertex takes its side's sum; one that corners of both sides use is split, a copy
    // taking the mirrored side's tangent and those corners.
    auto frame = [&](size_t i, uint8_t side) {
        const glm::vec3 nrm = safeNormalize(p.vertices[i].normal, glm::vec3(0, 0, 1));
        const glm::vec3& s = sum[2 * size_t(weld[i]) + side];
        const glm::vec3 t = s - nrm * glm::dot(nrm, s);
        const float len = glm::length(t);
        if (!(len > 1e-12f) || !std::isfinite(len))
            return glm::vec4(anyPerpendicular(nrm), 1.0f);  // no uv gradient reaches it
        return glm::vec4(t / len, side == 0 ? 1.0f : -1.0f);
    };
    std::vector<uint8_t> sides(n, 0);  // bit 1 << side: a corner of that side uses the vertex
    for (size_t c = 0; c < p.indices.size(); ++c)
        if (cornerValid[c]) sides[p.indices[c]] |= uint8_t(1u << cornerSide[c]);
    std::vector<uint32_t> copiedFrom, twin(n, UINT32_MAX);
    for (size_t i = 0; i < n; ++i) {
        p.vertices[i].tangent = frame(i, sides[i] == 2 ? 1 : 0);
        if (sides[i] == 3) {
            twin[i] = static_cast<uint32_t>(n + copiedFrom.size());
            copiedFrom.push_back(static_cast<uint32_t>(i));
        }
    }
    for (uint32_t i : copiedFrom) {
        Vertex copy = p.vertices[i];
        copy.tangent = frame(i, 1);
        p.vertices.push_back(copy);
    }
    for (size_t c = 0; c < p.indices.size(); ++c)
        if (cornerValid[c] && cornerSide[c] == 1 && twin[p.indices[c]] != UINT32_MAX)
            p.indices[c] = twin[p.indices[c]];
    return copiedFrom;
}

void generateFlatNormals(Primitive& p) {
    std::vector<Vertex> out;
    out.reserve(p.indices.size());
    for (size_t t = 0; t + 2 < p.indices.size(); t += 3) {
        Vertex tri[3];
        for (int k = 0; k < 3; ++k) tri[k] = p.vertices.at(p.indices[t + size_t(k)]);
        const glm::vec3 fn = safeNormalize(
            glm::cross(tri[1].position - tri[0].position, tri[2].position - tri[0].position),
            glm::vec3(0, 0, 1));
        for (auto& v : tri) {
            v.normal = fn;
            out.push_back(v);
        }
    }
    p.vertices = std::move(out);
    p.indices.resize(p.vertices.size());
    for (size_t i = 0; i < p.indices.size(); ++i) p.indices[i] = static_cast<uint32_t>(i);
}

Primitive makeSphere(float radius, uint32_t segments, uint32_t material) {
    Primitive p;
    p.material = material;
    segments = std::max(segments, 3u);
    const uint32_t rings = std::max(segments / 2, 2u);
    const float pi = 3.14159265358979f;
    // theta from the +Y pole (v = 0) to the -Y pole (v = 1); phi around +Y with u. The seam is
    // duplicated (u = 0 and u = 1) and so is each pole vertex, one per segment, so uvs and
    // tangents stay continuous per triangle.
    for (uint32_t r = 0; r <= rings; ++r) {
        const float v = float(r) / float(rings);
        const float theta = v * pi;
        for (uint32_t s = 0; s <= segments; ++s) {
            const float u = float(s) / float(segments);
            const float phi = u * 2.0f * pi;
            Vertex vert;
            // Going around with growing u turns clockwise seen from +Y (phi -> -phi), so that u
            // grows to the right for a viewer outside the sphere (image not mirrored).
            const glm::vec3 n(std::sin(theta) * std::cos(phi), std::cos(theta),
                              -std::sin(theta) * std::sin(phi));
            vert.normal = n;
            vert.position = n * radius;
            vert.uv0 = vert.uv1 = glm::vec2(u, v);
            // dP/du ~ (-sin phi, 0, -cos phi); the bitangent (-dP/dv) points towards +Y.
            const glm::vec3 t(-std::sin(phi), 0.0f, -std::cos(phi));
            const glm::vec3 b(-std::cos(theta) * std::cos(phi), std::sin(theta),
                              std::cos(theta) * std::sin(phi));
            const float w = glm::dot(glm::cross(n, t), b) < 0.0f ? -1.0f : 1.0f;
            vert.tangent = glm::vec4(t, w);
            p.vertices.push_back(vert);
        }
    }
    // The lightmap chart is the uv square itself: one chart, its border the atlas rect's (the seam
    // at u = 0 / 1 and the poles are where the bake's texels meet).
    p.lightmapUv = true;
    // The triangles over every `stride`-th ring and segment of the grid (1: all of them).
    const uint32_t row = segments + 1;
    auto triangles = [&](uint32_t stride) {
        std::vector<uint32_t> out;
        const uint32_t ringsAt = rings / stride, segmentsAt = segments / stride;
        for (uint32_t r = 0; r < ringsAt; ++r)
            for (uint32_t s = 0; s < segmentsAt; ++s) {
                const uint32_t a = r * stride * row + s * stride, b = a + stride,
                               c = a + stride * row, d = c + stride;
                // a-b on the upper ring, c-d below; u grows to the right seen from outside.
                if (r != 0) out.insert(out.end(), {a, c, b});
                if (r != ringsAt - 1) out.insert(out.end(), {b, c, d});
            }
        return out;
    };
    p.indices = triangles(1);
    // Levels of detail on every 2nd, 4th, 8th ring and segment, down to 24 segments: the same
    // vertices, so normals, uvs and the lightmap chart stay exact. A triangle of the grid spans at
    // most Δ = 2π / segments along each direction, so the sphere bulges above it by at most the
    // sagitta of its circumcircle, r (1 − cos(Δ / √2)) — which bounds its distance from the full
    // mesh too (the full mesh lies between the sphere and the coarser chords). The floor of 24
    // segments (Δ = 15°) bounds what the distance cannot: the shading normal interpolated across a
    // triangle, which at 8 segments (45°) turned a mirror-like sphere's point-light highlight into
    // a broad grey one however small the sphere was on screen.
    for (uint32_t stride = 2;
         stride <= 8 && segments % stride == 0 && rings % stride == 0 && segments / stride >= 24;
         stride *= 2) {
        const float delta = 2.0f * pi / float(segments / stride);
        p.lods.push_back({triangles(stride), radius * (1.0f - std::cos(delta / std::sqrt(2.0f)))});
    }
    return p;
}

Primitive makePlane(float width, float depth, uint32_t material) {
    Primitive p;
    p.material = material;
    const float hw = width * 0.5f, hd = depth * 0.5f;
    // u along +x, v along +z: seen from above, the image's top edge is at -z.
    const glm::vec3 pos[4] = {{-hw, 0, -hd}, {hw, 0, -hd}, {hw, 0, hd}, {-hw, 0, hd}};
    const glm::vec2 uv[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    for (int i = 0; i < 4; ++i) {
        Vertex v;
        v.position = pos[i];
        v.normal = glm::vec3(0, 1, 0);
        v.uv0 = v.uv1 = uv[i];
        v.tangent = glm::vec4(1, 0, 0, 1);
        p.vertices.push_back(v);
    }
    p.indices = {0, 3, 2, 0, 2, 1};
    p.lightmapUv = true;  // one chart: the uv square
    return p;
}

Primitive makeDisk(float radius, uint32_t segments, uint32_t material) {
    Primitive p;
    p.material = material;
    segments = std::max(segments, 3u);
    const float pi = 3.14159265358979f;
    // The centre, then the rim counter-clockwise seen from +Y (the angle from +X towards −Z).
    Vertex centre;
    centre.normal = glm::vec3(0, 1, 0);
    centre.tangent = glm::vec4(1, 0, 0, 1);
    centre.uv0 = centre.uv1 = glm::vec2(0.5f);
    p.vertices.push_back(centre);
    for (uint32_t s = 0; s < segments; ++s) {
        const float a = 2.0f * pi * float(s) / float(segments);
        Vertex v = centre;
        v.position = glm::vec3(std::cos(a), 0.0f, -std::sin(a)) * radius;
        v.uv0 = v.uv1 = glm::vec2(0.5f + 0.5f * std::cos(a), 0.5f + 0.5f * std::sin(a));
        p.vertices.push_back(v);
    }
    for (uint32_t s = 0; s < segments; ++s)
        p.indices.insert(p.indices.end(), {0, 1 + s, 1 + (s + 1) % segments});
    p.lightmapUv = true;  // one chart: the disk inscribed in the uv square
    return p;
}

Primitive makeCapsule(float radius, float length, uint32_t segments, uint32_t material) {
    Primitive p;
    p.material = material;
    segments = std::max(segments, 3u);
    const uint32_t half = std::max(segments / 4, 1u);  // rings per hemisphere
    const float pi = 3.14159265358979f;
    // Rings from the +Y pole to the equator, raised by length / 2, then from the equator to the
    // −Y pole, lowered by length / 2: the band between the two equators is the cylinder.
    std::vector<std::pair<float, float>> rings;  // polar angle, offset along Y
    for (uint32_t r = 0; r <= half; ++r)
        rings.emplace_back(0.5f * pi * float(r) / float(half), 0.5f * length);
    for (uint32_t r = 0; r <= half; ++r)
        rings.emplace_back(0.5f * pi * (1.0f + float(r) / float(half)), -0.5f * length);
    for (size_t r = 0; r < rings.size(); ++r)
        for (uint32_t s = 0; s <= segments; ++s) {
            const auto [theta, offset] = rings[r];
            const float u = float(s) / float(segments), phi = u * 2.0f * pi;
            const glm::vec3 n(std::sin(theta) * std::cos(phi), std::cos(theta),
                              -std::sin(theta) * std::sin(phi));
            Vertex v;
            v.normal = n;
            v.position = n * radius + glm::vec3(0.0f, offset, 0.0f);
            v.uv0 = v.uv1 = glm::vec2(u, float(r) / float(rings.size() - 1));
            v.tangent = glm::vec4(-std::sin(phi), 0.0f, -std::cos(phi), 1.0f);
            p.vertices.push_back(v);
        }
    const uint32_t row = segments + 1, last = static_cast<uint32_t>(rings.size() - 1);
    for (uint32_t r = 0; r < last; ++r)
        for (uint32_t s = 0; s < segments; ++s) {
            const uint32_t a = r * row + s, b = a + 1, c = a + row, d = c + 1;
            if (r != 0) p.indices.insert(p.indices.end(), {a, c, b});
            if (r != last - 1) p.indices.insert(p.indices.end(), {b, c, d});
        }
    return p;
}

Primitive makeBox(glm::vec3 size, uint32_t material) {
    Primitive p;
    p.material = material;
    const glm::vec3 h = size * 0.5f;
    // Each face: its normal and the direction u grows in (seen from outside, v grows downwards).
    const glm::vec3 faces[6][2] = {{{1, 0, 0}, {0, 0, -1}}, {{-1, 0, 0}, {0, 0, 1}},
                                   {{0, 1, 0}, {1, 0, 0}},  {{0, -1, 0}, {1, 0, 0}},
                                   {{0, 0, 1}, {1, 0, 0}},  {{0, 0, -1}, {-1, 0, 0}}};
    // Lightmap uvs: the six faces in a 3 × 2 grid of cells, each face inset by kBoxChartInset of its
    // cell so that neighbouring charts keep a gutter (packLightmap gives a box at least
    // kMinBoxLightmapTexels per side: ≥ 2 texels between faces).
    int face = 0;
    for (const auto& f : faces) {
        const glm::vec2 cell(float(face % 3) / 3.0f, float(face / 3) / 2.0f),
            cellSize(1.0f / 3.0f, 0.5f);
        ++face;
        const glm::vec3 n = f[0], right = f[1], up = glm::cross(n, right);
        const uint32_t base = static_cast<uint32_t>(p.vertices.size());
        const glm::vec2 uv[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
        for (int i = 0; i < 4; ++i) {
            const float sx = uv[i].x * 2.0f - 1.0f, sy = 1.0f - uv[i].y * 2.0f;
            Vertex v;
            v.position = (n + right * sx + up * sy) * h;
            v.normal = n;
            v.uv0 = uv[i];
            v.uv1 = cell + cellSize * (kBoxChartInset + uv[i] * (1.0f - 2.0f * kBoxChartInset));
            v.tangent = glm::vec4(right, 1.0f);  // bitangent cross(n, right) = up = -dP/dv
            p.vertices.push_back(v);
        }
        // (0,0) top-left, (1,0) top-right, (1,1) bottom-right, (0,1) bottom-left: CCW from outside.
        p.indices.insert(p.indices.end(), {base, base + 3, base + 2, base, base + 2, base + 1});
    }
    p.lightmapUv = true;
    return p;
}

void computeBounds(Scene& scene) {
    glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
    bool any = false;
    for (const auto& node : scene.nodes) {
        if (node.mesh < 0 || size_t(node.mesh) >= scene.meshes.size()) continue;
        const Mesh& mesh = scene.meshes[size_t(node.mesh)];
        for (const auto* list : {&mesh.primitives, &mesh.lines, &mesh.points})
            for (const auto& prim : *list)
                for (const auto& v : prim.vertices) {
                    const glm::vec3 w = glm::vec3(node.world * glm::vec4(v.position, 1.0f));
                    lo = glm::min(lo, w);
                    hi = glm::max(hi, w);
                    any = true;
                }
    }
    scene.boundsMin = any ? lo : glm::vec3(0.0f);
    scene.boundsMax = any ? hi : glm::vec3(0.0f);
}

}  // namespace rg

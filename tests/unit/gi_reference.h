// An independent reference for baked GI (tests/unit/test_lightmap.cpp, tests/gpu/test_lightmap_render.cpp):
// Monte Carlo irradiance and radiance in a scene of Lambertian triangles lit by rect lights, written
// without the baker's parts — every triangle tested per ray (Möller–Trumbore), directions
// cosine-distributed, the lights sampled uniformly over their area (seed 000 tbl:12 for their
// luminance), `bounces` surfaces lit along each path.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace rg::test {

// An independent estimate of irradiance in a scene of Lambertian triangles and rect lights: every
// triangle tested per ray (Möller–Trumbore), directions cosine-distributed, the lights sampled
// uniformly over their area; emission and bounces as the issue states (≥ 2 bounces).
inline constexpr double kGiPi = 3.14159265358979323846;

struct BruteForceGi {
    struct Tri {
        glm::vec3 a, b, c, n;
        glm::vec3 albedo, emission;
    };
    struct RectLight {
        glm::vec3 centre, normal, u, v;  // u, v: half extents
        glm::vec3 luminance;
    };
    std::vector<Tri> tris;
    std::vector<RectLight> lights;
    int bounces = 3;

    explicit BruteForceGi(const rg::Scene& s) {
        for (const auto& node : s.nodes)
            for (const auto& p : s.meshes[size_t(node.mesh)].primitives) {
                const rg::Material& m = s.materials[p.material];
                for (size_t t = 0; t + 2 < p.indices.size(); t += 3) {
                    Tri tri;
                    tri.a =
                        glm::vec3(node.world * glm::vec4(p.vertices[p.indices[t]].position, 1.0f));
                    tri.b = glm::vec3(node.world *
                                      glm::vec4(p.vertices[p.indices[t + 1]].position, 1.0f));
                    tri.c = glm::vec3(node.world *
                                      glm::vec4(p.vertices[p.indices[t + 2]].position, 1.0f));
                    tri.n = glm::normalize(glm::cross(tri.b - tri.a, tri.c - tri.a));
                    tri.albedo = m.baseColor * (1.0f - m.metalMask);
                    tri.emission = m.emissive;
                    tris.push_back(tri);
                }
            }
        for (const auto& l : s.lights) {
            EXPECT_EQ(l.type, rg::LightType::Rect);
            EXPECT_EQ(l.unit, "lm");
            RectLight r;
            r.centre = l.position;
            r.normal = l.direction;
            const glm::vec3 up = glm::normalize(l.up - glm::dot(l.up, l.direction) * l.direction);
            r.v = up * (0.5f * l.height);
            r.u = glm::normalize(glm::cross(l.direction, up)) * (0.5f * l.width);
            // Seed 000 tbl:12: a one-sided Lambertian emitter, L = Φ / (π A).
            r.luminance = l.color * float(l.intensity / (kGiPi * l.width * l.height));
            lights.push_back(r);
        }
    }
    // Nearest hit: triangle index and distance.
    std::pair<int, float> hit(glm::vec3 o, glm::vec3 d, float tMax) const {
        int best = -1;
        for (size_t i = 0; i < tris.size(); ++i) {
            const glm::vec3 e1 = tris[i].b - tris[i].a, e2 = tris[i].c - tris[i].a,
                            pv = glm::cross(d, e2);
            const float det = glm::dot(e1, pv);
            if (std::abs(det) < 1e-12f) continue;
            const float inv = 1.0f / det;
            const glm::vec3 tv = o - tris[i].a;
            const float u = glm::dot(tv, pv) * inv;
            if (u < 0.0f || u > 1.0f) continue;
            const glm::vec3 qv = glm::cross(tv, e1);
            const float v = glm::dot(d, qv) * inv;
            if (v < 0.0f || u + v > 1.0f) continue;
            const float t = glm::dot(e2, qv) * inv;
            if (t > 1e-4f && t < tMax) tMax = t, best = int(i);
        }
        return {best, tMax};
    }
    glm::vec3 direct(glm::vec3 p, glm::vec3 n, std::mt19937& rng) const {
        std::uniform_real_distribution<float> U(-1.0f, 1.0f);
        glm::vec3 e(0.0f);
        for (const auto& l : lights) {
            const glm::vec3 q = l.centre + l.u * U(rng) + l.v * U(rng);
            const glm::vec3 v = q - p;
            const float d2 = glm::dot(v, v), d = std::sqrt(d2);
            const glm::vec3 w = v / d;
            const float cs = glm::dot(n, w), cl = -glm::dot(l.normal, w);
            if (cs <= 0.0f || cl <= 0.0f) continue;
            if (hit(p, w, d - 1e-3f).first >= 0) continue;
            e += l.luminance * (cs * cl * 4.0f * glm::length(l.u) * glm::length(l.v) / d2);
        }
        return e;
    }
    glm::vec3 cosineDir(glm::vec3 n, std::mt19937& rng) const {
        std::uniform_real_distribution<float> U(0.0f, 1.0f);
        const float r = std::sqrt(U(rng)), phi = float(2.0 * kGiPi) * U(rng);
        const glm::vec3 t =
            glm::normalize(std::abs(n.x) < 0.9f ? glm::cross(n, glm::vec3(1, 0, 0))
                                                : glm::cross(n, glm::vec3(0, 1, 0)));
        const glm::vec3 b = glm::cross(n, t);
        return t * (r * std::cos(phi)) + b * (r * std::sin(phi)) +
               n * std::sqrt(std::max(0.0f, 1.0f - r * r));
    }
    // Radiance leaving the first surface along -d.
    glm::vec3 radiance(glm::vec3 o, glm::vec3 d, int depth, std::mt19937& rng) const {
        const auto [i, t] = hit(o, d, 1e30f);
        if (i < 0) return glm::vec3(0.0f);
        const Tri& tri = tris[size_t(i)];
        if (glm::dot(tri.n, d) > 0.0f) return glm::vec3(0.0f);
        const glm::vec3 p = o + d * t + tri.n * 1e-4f;
        glm::vec3 e = direct(p, tri.n, rng);
        if (depth > 1) e += float(kGiPi) * radiance(p, cosineDir(tri.n, rng), depth - 1, rng);
        return tri.emission + tri.albedo / float(kGiPi) * e;
    }
    // Irradiance at p (normal n): direct from the lights + indirect, `paths` samples.
    glm::vec3 irradiance(glm::vec3 p, glm::vec3 n, int paths, uint32_t seed) const {
        std::mt19937 rng(seed);
        glm::dvec3 sum(0.0);
        for (int s = 0; s < paths; ++s)
            sum += glm::dvec3(direct(p, n, rng) +
                              float(kGiPi) * radiance(p, cosineDir(n, rng), bounces, rng));
        return glm::vec3(sum / double(paths));
    }
};

}  // namespace rg::test

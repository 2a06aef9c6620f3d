// The SG lightmap baker: Monte Carlo path tracing on the CPU, ray casts by Intel Embree, the
// projection onto the fixed SG basis fitted under non-negativity (lighting::fitNonNegative).
//
// Per covered texel (the closest triangle of the node's charts within 0.75 texel of its centre,
// conservatively, so bilinear filtering at a chart's edge reads baked texels) and per path:
//   1. a point jittered over the texel, clamped onto its triangle, with the interpolated tangent frame;
//   2. a direction ω uniform over the frame's upper hemisphere (stratified, pdf 1 / 2π); the radiance
//      L(ω) arriving along it is traced: the environment on a miss; at a hit, its emission plus its
//      Lambertian reflection of every light's direct illuminance (shadow rays) and — for `bounces`
//      surfaces in all — of the light arriving there (one cosine-distributed ray each);
//   3. the projections ∫ G_k L dω += G_k(ω) L(ω) / pdf, averaged over the paths; and for each light
//      marked baked, its direct light at the texel as a delta of illuminance E from direction d:
//      + E · G_k(d) (an area light: one point sampled on it per path).
// Then the non-negative least-squares fit on the hemisphere's exact Gram matrix, and a dilation of
// the covered texels into the border around every node's square (dilateLightmap; a shard leaves
// that to the merge).
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <mutex>
#include <thread>

#include <embree3/rtcore.h>

#include "bake/lightmap.h"
#include "lighting/punctual.h"
#include "lighting/sg.h"
#include "lighting/light_table.h"
#include "scene/environment.h"

namespace rg::bake {

using lighting::GpuLight;
using lighting::GpuLightType;

namespace {

constexpr float kPi = 3.14159265358979f;

// A small, fast generator (PCG32), seeded per texel so a bake does not depend on the threads.
struct Rng {
    uint64_t state;
    explicit Rng(uint64_t seed) : state(seed * 6364136223846793005ull + 1442695040888963407ull) {
        next();
    }
    uint32_t next() {
        const uint64_t old = state;
        state = old * 6364136223846793005ull + 1442695040888963407ull;
        const uint32_t x = static_cast<uint32_t>(((old >> 18u) ^ old) >> 27u),
                       r = static_cast<uint32_t>(old >> 59u);
        return (x >> r) | (x << ((32u - r) & 31u));
    }
    float uniform() { return float(next() >> 8) * (1.0f / 16777216.0f); }
};

struct Frame {
    glm::vec3 t, b, n;
    glm::vec3 toWorld(glm::vec3 v) const { return t * v.x + b * v.y + n * v.z; }
};

// lib/material.glsl's frame: the interpolated normal, the tangent made perpendicular to it (any
// perpendicular vector when degenerate), the bitangent cross(n, t) × handedness.
Frame tangentFrame(glm::vec3 n, glm::vec4 tangent) {
    n = glm::normalize(n);
    glm::vec3 t = glm::vec3(tangent) - n * glm::dot(n, glm::vec3(tangent));
    const float tl = glm::dot(t, t);
    const glm::vec3 anyT = glm::normalize(std::abs(n.x) < 0.9f ? glm::cross(n, glm::vec3(1, 0, 0))
                                                               : glm::cross(n, glm::vec3(0, 1, 0)));
    t = tl > 1e-12f ? t / std::sqrt(tl) : anyT;
    return {t, glm::cross(n, t) * (tangent.w < 0.0f ? -1.0f : 1.0f), n};
}

// The world-space triangles of one node's primitive.
struct Part {
    size_t node = 0, primitive = 0;
    glm::mat4 world{1.0f};
    glm::mat3 normalMatrix{1.0f};
    const Primitive* prim = nullptr;
    const Material* material = nullptr;
};

struct Surface {
    glm::vec3 position, geometricNormal;
    Frame frame;
    glm::vec2 uv0;
};

Surface surfaceAt(const Part& part, uint32_t triangle, float u, float v) {
    const Primitive& p = *part.prim;
    const Vertex& a = p.vertices[p.indices[3 * triangle]];
    const Vertex& b = p.vertices[p.indices[3 * triangle + 1]];
    const Vertex& c = p.vertices[p.indices[3 * triangle + 2]];
    const float w = 1.0f - u - v;
    Surface s;
    s.position =
        glm::vec3(part.world * glm::vec4(a.position * w + b.position * u + c.position * v, 1.0f));
    const glm::vec3 pa = glm::vec3(part.world * glm::vec4(a.position, 1.0f)),
                    pb = glm::vec3(part.world * glm::vec4(b.position, 1.0f)),
                    pc = glm::vec3(part.world * glm::vec4(c.position, 1.0f));
    glm::vec3 ng = glm::cross(pb - pa, pc - pa);
    ng = glm::length(ng) > 0.0f ? glm::normalize(ng) : glm::vec3(0, 1, 0);
    s.geometricNormal = ng;
    const glm::vec3 n = part.normalMatrix * (a.normal * w + b.normal * u + c.normal * v);
    const glm::vec4 t = a.tangent * w + b.tangent * u + c.tangent * v;
    s.frame = tangentFrame(glm::length(n) > 0.0f ? n : ng,
                           glm::vec4(glm::mat3(part.world) * glm::vec3(t), a.tangent.w));
    s.uv0 = a.uv0 * w + b.uv0 * u + c.uv0 * v;
    return s;
}

// Nearest texel of a texture (level 0, repeat), RGB; sRGB decoded.
glm::vec3 textureRgb(const Scene& scene, const TextureRef& ref, glm::vec2 uv0) {
    if (ref.image < 0 || size_t(ref.image) >= scene.images.size()) return glm::vec3(1.0f);
    const SceneImage& img = scene.images[size_t(ref.image)];
    const Image& px = img.pixels;
    if (px.width == 0 || px.height == 0 || px.channels < 3) return glm::vec3(1.0f);
    const glm::vec2 uv = glm::vec2(ref.transform * glm::vec3(uv0, 1.0f));
    const float fx = uv.x - std::floor(uv.x), fy = uv.y - std::floor(uv.y);
    const uint32_t x = std::min(px.width - 1, static_cast<uint32_t>(fx * float(px.width)));
    const uint32_t y = std::min(px.height - 1, static_cast<uint32_t>(fy * float(px.height)));
    glm::vec3 c(px.at(x, y, 0), px.at(x, y, 1), px.at(x, y, 2));
    if (img.srgb)
        for (int i = 0; i < 3; ++i) c[i] = srgbDecode(c[i]);
    return c;
}

glm::vec3 diffuseAlbedo(const Scene& scene, const Material& m, glm::vec2 uv0) {
    if (m.model == "two_colour") return m.diffuseColor * textureRgb(scene, m.baseColorTex, uv0);
    return m.baseColor * textureRgb(scene, m.baseColorTex, uv0) * (1.0f - m.metalMask);
}

// Emitted luminance; emission given relative to the exposure (Material::emissiveEv) is baked at
// kEmissiveEv100WithoutExposure, as the probes capture it: a bake knows no camera.
glm::vec3 emission(const Scene& scene, const Material& m, glm::vec2 uv0) {
    if (m.emissive == glm::vec3(0.0f)) return glm::vec3(0.0f);
    const float scale =
        m.emissiveEv ? std::exp2(m.emissiveEc + kEmissiveEv100WithoutExposure - 3.0f) : 1.0f;
    return m.emissive * scale * textureRgb(scene, m.emissiveTex, uv0);
}

class Tracer {
public:
    Tracer(const Scene& scene) : m_scene(scene) {}
    ~Tracer() {
        if (m_rtcScene) rtcReleaseScene(m_rtcScene);
        if (m_device) rtcReleaseDevice(m_device);
    }

    Result<void> build() {
        m_device = rtcNewDevice(nullptr);
        if (!m_device)
            return fail(ErrorCode::Unsupported,
                        "Embree: cannot create a device (" +
                            std::to_string(int(rtcGetDeviceError(nullptr))) + ")");
        m_rtcScene = rtcNewScene(m_device);
        for (size_t ni = 0; ni < m_scene.nodes.size(); ++ni) {
            const Node& node = m_scene.nodes[ni];
            if (node.mesh < 0 || size_t(node.mesh) >= m_scene.meshes.size()) continue;
            const Mesh& mesh = m_scene.meshes[size_t(node.mesh)];
            for (size_t pi = 0; pi < mesh.primitives.size(); ++pi) {
                const Primitive& p = mesh.primitives[pi];
                if (p.indices.size() < 3 || p.material >= m_scene.materials.size()) continue;
                Part part;
                part.node = ni;
                part.primitive = pi;
                part.world = node.world;
                part.normalMatrix = glm::transpose(glm::inverse(glm::mat3(node.world)));
                part.prim = &p;
                part.material = &m_scene.materials[p.material];
                RTCGeometry g = rtcNewGeometry(m_device, RTC_GEOMETRY_TYPE_TRIANGLE);
                auto* v = static_cast<float*>(
                    rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                            3 * sizeof(float), p.vertices.size()));
                for (size_t i = 0; i < p.vertices.size(); ++i) {
                    const glm::vec3 w =
                        glm::vec3(node.world * glm::vec4(p.vertices[i].position, 1.0f));
                    v[3 * i] = w.x, v[3 * i + 1] = w.y, v[3 * i + 2] = w.z;
                }
                const size_t tris = p.indices.size() / 3;
                auto* idx = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(
                    g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(uint32_t), tris));
                for (size_t i = 0; i < tris * 3; ++i)
                    idx[i] = std::min<uint32_t>(p.indices[i], uint32_t(p.vertices.size() - 1));
                rtcCommitGeometry(g);
                const uint32_t id = rtcAttachGeometry(m_rtcScene, g);
                rtcReleaseGeometry(g);
                if (m_parts.size() <= id) m_parts.resize(id + 1);
                m_parts[id] = part;
            }
        }
        rtcCommitScene(m_rtcScene);
        if (rtcGetDeviceError(m_device) != RTC_ERROR_NONE)
            return fail(ErrorCode::InvalidInput, "Embree: building the scene's BVH failed");
        RTCBounds b;
        rtcGetSceneBounds(m_rtcScene, &b);
        m_epsilon = 1e-4f * std::max(1.0f, glm::length(glm::vec3(b.upper_x - b.lower_x,
                                                                 b.upper_y - b.lower_y,
                                                                 b.upper_z - b.lower_z)));
        return {};
    }

    const std::vector<Part>& parts() const { return m_parts; }
    float epsilon() const { return m_epsilon; }

    struct Hit {
        bool hit = false;
        uint32_t geom = 0, prim = 0;
        float u = 0, v = 0, t = 0;
        glm::vec3 ng{0.0f};
    };
    Hit intersect(glm::vec3 o, glm::vec3 d, uint64_t& rays, float tMax = INFINITY) const {
        RTCIntersectContext ctx;
        rtcInitIntersectContext(&ctx);
        RTCRayHit rh{};
        rh.ray.org_x = o.x, rh.ray.org_y = o.y, rh.ray.org_z = o.z;
        rh.ray.dir_x = d.x, rh.ray.dir_y = d.y, rh.ray.dir_z = d.z;
        rh.ray.tnear = 0.0f;
        rh.ray.tfar = tMax;
        rh.ray.mask = 0xffffffffu;
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(m_rtcScene, &ctx, &rh);
        ++rays;
        Hit h;
        if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return h;
        h.hit = true;
        h.geom = rh.hit.geomID, h.prim = rh.hit.primID, h.u = rh.hit.u, h.v = rh.hit.v,
        h.t = rh.ray.tfar;
        h.ng = glm::vec3(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z);
        return h;
    }
    bool occluded(glm::vec3 o, glm::vec3 d, float tMax, uint64_t& rays) const {
        RTCIntersectContext ctx;
        rtcInitIntersectContext(&ctx);
        RTCRay r{};
        r.org_x = o.x, r.org_y = o.y, r.org_z = o.z;
        r.dir_x = d.x, r.dir_y = d.y, r.dir_z = d.z;
        r.tnear = 0.0f;
        r.tfar = tMax;
        r.mask = 0xffffffffu;
        rtcOccluded1(m_rtcScene, &ctx, &r);
        ++rays;
        return r.tfar < 0.0f;
    }

private:
    const Scene& m_scene;
    RTCDevice m_device = nullptr;
    RTCScene m_rtcScene = nullptr;
    std::vector<Part> m_parts;  // by Embree geometry id
    float m_epsilon = 1e-4f;
};

// A direction towards a light and the illuminance it brings a surface facing it (lux, RGB):
// one sample (area lights: one point on the light).
struct LightSample {
    glm::vec3 direction{0.0f};    // unit, from the surface towards the light
    float distance = 0.0f;        // to the sampled point (INFINITY: the sun)
    glm::vec3 illuminance{0.0f};  // perpendicular to `direction`, before the surface's cosine
};

LightSample sampleLight(const GpuLight& g, glm::vec3 p, Rng& rng) {
    LightSample s;
    const auto type = static_cast<GpuLightType>(static_cast<int>(g.positionType.w));
    const glm::vec3 pos(g.positionType), dir(g.directionRange), colour(g.intensity);
    const float invSqrRange = g.directionRange.w;
    if (type == GpuLightType::Sun) {
        s.direction = -dir;
        s.distance = INFINITY;
        s.illuminance = colour;  // lux
        return s;
    }
    if (type == GpuLightType::Point || type == GpuLightType::Spot) {
        const glm::vec3 v = pos - p;
        s.distance = glm::length(v);
        if (!(s.distance > 0.0f)) return s;
        s.direction = v / s.distance;
        // lst:4: the windowed inverse square and the cone.
        const float att = lighting::getDistanceAtt(v, invSqrRange) *
                          lighting::getAngleAtt(-s.direction, dir, g.params.x, g.params.y);
        s.illuminance = colour * att;  // cd × 1/d² = lux
        return s;
    }
    // Area lights: a point uniform over the emitting surface, luminance L (cd/m²):
    // E = L cos θ_light A / d² (the surface's cosine comes later).
    glm::vec3 q, nq;
    float area = 0.0f;
    const float u1 = rng.uniform(), u2 = rng.uniform();
    auto onSphere = [](float a, float b) {
        const float z = 1.0f - 2.0f * a, r = std::sqrt(std::max(0.0f, 1.0f - z * z)),
                    phi = 2.0f * kPi * b;
        return glm::vec3(r * std::cos(phi), r * std::sin(phi), z);
    };
    const float radius = g.params.z;
    if (type == GpuLightType::Sphere) {
        nq = onSphere(u1, u2);
        q = pos + radius * nq;
        area = 4.0f * kPi * radius * radius;
    } else if (type == GpuLightType::Disk || type == GpuLightType::Rect) {
        const Frame f = tangentFrame(
            dir, glm::vec4(type == GpuLightType::Rect ? glm::vec3(g.axis) : glm::vec3(1, 0, 0),
                           1.0f));  // disks: any frame
        if (type == GpuLightType::Disk) {
            const float r = radius * std::sqrt(u1), phi = 2.0f * kPi * u2;
            q = pos + f.t * (r * std::cos(phi)) + f.b * (r * std::sin(phi));
            area = kPi * radius * radius;
        } else {
            const float width = g.params.w, height = g.axis.w;
            q = pos + f.t * ((u1 - 0.5f) * height) + f.b * ((u2 - 0.5f) * width);
            area = width * height;
        }
        nq = dir;  // one-sided: it emits along its direction
    } else {       // tube: a capsule along `dir`, its cylinder and its two half-sphere caps by area
        const float length = g.params.w;
        const float side = 2.0f * kPi * radius * length, caps = 4.0f * kPi * radius * radius;
        area = side + caps;
        const Frame f = tangentFrame(dir, glm::vec4(1, 0, 0, 1));
        const float pick = rng.uniform() * area;
        if (pick < side) {
            const float phi = 2.0f * kPi * u2;
            nq = f.t * std::cos(phi) + f.b * std::sin(phi);
            q = pos + dir * ((u1 - 0.5f) * length) + radius * nq;
        } else {
            nq = onSphere(u1, u2);
            q = pos + dir * (glm::dot(nq, dir) >= 0.0f ? 0.5f * length : -0.5f * length) +
                radius * nq;
        }
    }
    const glm::vec3 v = q - p;
    const float d2 = glm::dot(v, v);
    if (!(d2 > 1e-12f)) return s;
    s.distance = std::sqrt(d2);
    s.direction = v / s.distance;
    // The sampled point's own cosine: a sphere's or tube's far side and a disk's or rect's back emit nothing.
    const float cosLight = glm::dot(nq, -s.direction);
    if (cosLight <= 0.0f) return s;
    // lst:4's window by the distance to the light's centre, as the real-time loop does.
    const glm::vec3 toCentre = pos - p;
    float window = invSqrRange > 0.0f
                       ? lighting::smoothDistanceAtt(glm::dot(toCentre, toCentre), invSqrRange)
                       : 1.0f;
    if (type == GpuLightType::Disk) {  // its cone (lst:9), as lighting.glsl's rgDiskCone
        const glm::vec3 apex = pos - dir * g.axis.w, toApex = apex - p;
        const float len = glm::length(toApex);
        window *=
            lighting::getAngleAtt(len > 0.0f ? -toApex / len : dir, dir, g.params.x, g.params.y);
    }
    s.illuminance = colour * (cosLight * area / d2 * window);
    return s;
}

// Cosine-distributed direction about +z.
glm::vec3 cosineHemisphere(float u1, float u2) {
    const float r = std::sqrt(u1), phi = 2.0f * kPi * u2;
    return glm::vec3(r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.0f, 1.0f - u1)));
}

struct Context {
    const Scene& scene;
    const Tracer& tracer;
    const std::vector<GpuLight>& lights;
    const Image& environment;
    int bounces = 2;
};

// Direct illuminance from every light at surface point p (normal n), shadowed; lux × the cosine.
glm::vec3 directLight(const Context& c, glm::vec3 p, glm::vec3 n, Rng& rng, uint64_t& rays) {
    glm::vec3 e(0.0f);
    for (const GpuLight& g : c.lights) {
        const LightSample s = sampleLight(g, p, rng);
        const float cosine = glm::dot(n, s.direction);
        if (cosine <= 0.0f || s.illuminance == glm::vec3(0.0f)) continue;
        const float eps = c.tracer.epsilon();
        if (c.tracer.occluded(p + n * eps, s.direction,
                              std::isinf(s.distance) ? INFINITY : s.distance * (1.0f - 1e-4f) - eps,
                              rays))
            continue;
        e += s.illuminance * cosine;
    }
    return e;
}

// The radiance arriving at o along d: the environment, or the surface hit, lit directly and by
// `depth` more bounces.
glm::vec3 radiance(const Context& c, glm::vec3 o, glm::vec3 d, int depth, Rng& rng,
                   uint64_t& rays) {
    const Tracer::Hit h = c.tracer.intersect(o, d, rays);
    if (!h.hit)
        return c.environment.width ? sampleEquirect(c.environment, equirectUv(d)) : glm::vec3(0.0f);
    const Part& part = c.tracer.parts()[h.geom];
    const Surface s = surfaceAt(part, h.prim, h.u, h.v);
    glm::vec3 ng = s.geometricNormal;
    const bool back = glm::dot(ng, d) > 0.0f;
    if (back && !part.material->doubleSided) return glm::vec3(0.0f);  // inside a closed object
    glm::vec3 n = s.frame.n;
    if (back) ng = -ng, n = -n;
    if (glm::dot(n, ng) <= 0.0f) n = ng;
    const glm::vec3 le = back ? glm::vec3(0.0f) : emission(c.scene, *part.material, s.uv0);
    const glm::vec3 albedo = diffuseAlbedo(c.scene, *part.material, s.uv0);
    if (albedo == glm::vec3(0.0f)) return le;
    const glm::vec3 p = s.position + ng * c.tracer.epsilon();
    glm::vec3 e = directLight(c, p, n, rng, rays);
    if (depth > 1) {
        // ∫ L cos dω by one cosine-distributed sample: π L.
        const Frame f = tangentFrame(n, glm::vec4(s.frame.t, 1.0f));
        const glm::vec3 w = f.toWorld(cosineHemisphere(rng.uniform(), rng.uniform()));
        if (glm::dot(w, ng) > 0.0f) e += kPi * radiance(c, p, w, depth - 1, rng, rays);
    }
    return le + albedo / kPi * e;
}

// The closest point of triangle abc to p (2D) as barycentrics (u for b, v for c).
glm::vec2 closestBarycentric(glm::vec2 p, glm::vec2 a, glm::vec2 b, glm::vec2 c) {
    // Ericson, Real-Time Collision Detection, 5.1.5, in 2D.
    const glm::vec2 ab = b - a, ac = c - a, ap = p - a;
    const float d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
    if (d1 <= 0.0f && d2 <= 0.0f) return {0, 0};
    const glm::vec2 bp = p - b;
    const float d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
    if (d3 >= 0.0f && d4 <= d3) return {1, 0};
    const float vc = d1 * d4 - d3 * d2;
    if (vc <= 0.0f && d1 >= 0.0f && d3 <= 0.0f) return {d1 / (d1 - d3), 0};
    const glm::vec2 cp = p - c;
    const float d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
    if (d6 >= 0.0f && d5 <= d6) return {0, 1};
    const float vb = d5 * d2 - d1 * d6;
    if (vb <= 0.0f && d2 >= 0.0f && d6 <= 0.0f) return {0, d2 / (d2 - d6)};
    const float va = d3 * d6 - d5 * d4;
    if (va <= 0.0f && (d4 - d3) >= 0.0f && (d5 - d6) >= 0.0f) {
        const float w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return {1.0f - w, w};
    }
    const float denom = 1.0f / (va + vb + vc);
    return {vb * denom, vc * denom};
}

struct TexelOwner {
    float distance = 1e30f;
    uint32_t part = 0, triangle = 0;
};

}  // namespace

Result<Lightmap> bakeLightmap(const Scene& scene, const LightmapAtlas& atlas,
                              const LightmapSettings& settings, const BakeOptions& options,
                              BakeStats* stats) {
    const auto start = std::chrono::steady_clock::now();
    if (atlas.rects.size() != scene.nodes.size())
        return fail(ErrorCode::InvalidInput, "lightmap: the atlas was packed for another scene");
    for (const Light& l : scene.lights)
        if (l.baked && !l.ies.empty())
            return fail(ErrorCode::InvalidInput,
                        "light '" + l.name +
                            "': a light with an IES profile cannot be baked (the baker does not "
                            "shape light by profiles); leave it dynamic");
    auto table = lighting::convertLights(scene.lights);
    if (!table) return std::unexpected(table.error());
    std::vector<GpuLight> allLights = table->lights, bakedLights;
    for (size_t i = 0; i < scene.lights.size(); ++i)
        if (scene.lights[i].baked) bakedLights.push_back(table->lights[i]);
    Image environment;
    if (scene.environment) {
        auto env = environmentImage(scene);
        if (!env) return std::unexpected(env.error());
        environment = std::move(*env);
    }
    Tracer tracer(scene);
    if (auto r = tracer.build(); !r) return std::unexpected(r.error());

    Lightmap lm;
    lm.width = atlas.width;
    lm.height = atlas.height;
    lm.axes = lightmapAxes(settings.lobes);
    lm.sharpness = lightmapSharpness(settings.lobes);
    lm.density = atlas.density;  // lm.key: prepareLightmap's, which hashed the scene already
    const size_t texels = size_t(lm.width) * lm.height;
    lm.lobes.assign(lm.axes.size(), std::vector<glm::vec3>(texels, glm::vec3(0.0f)));
    lm.coverage.assign(texels, 0);
    if (texels == 0) return lm;

    // Which triangle owns each texel: the nearest within 0.75 texel (in the atlas's texel units).
    std::vector<TexelOwner> owner(texels);
    const auto& parts = tracer.parts();
    for (uint32_t pi = 0; pi < parts.size(); ++pi) {
        const Part& part = parts[pi];
        if (!part.prim) continue;
        const glm::vec4 rect = atlas.rects[part.node];
        const glm::uvec4 tr = atlas.texelRects[part.node];
        const Primitive& p = *part.prim;
        for (uint32_t t = 0; t < p.indices.size() / 3; ++t) {
            glm::vec2 c[3];
            for (int k = 0; k < 3; ++k) {
                const glm::vec2 uv = p.vertices[std::min<size_t>(p.indices[3 * t + uint32_t(k)],
                                                                 p.vertices.size() - 1)]
                                         .uv1;
                c[k] = (uv * glm::vec2(rect) + glm::vec2(rect.z, rect.w)) *
                       glm::vec2(lm.width, lm.height);
            }
            const glm::vec2 lo = glm::min(c[0], glm::min(c[1], c[2])) - 1.0f,
                            hi = glm::max(c[0], glm::max(c[1], c[2])) + 1.0f;
            // Stay inside the node's square and its border.
            const int x0 = std::max(int(std::floor(lo.x)), int(tr.x) - 1),
                      x1 = std::min(int(std::ceil(hi.x)), int(tr.x + tr.z));
            const int y0 = std::max(int(std::floor(lo.y)), int(tr.y) - 1),
                      y1 = std::min(int(std::ceil(hi.y)), int(tr.y + tr.z));
            for (int y = y0; y <= y1; ++y)
                for (int x = x0; x <= x1; ++x) {
                    if (x < 0 || y < 0 || x >= int(lm.width) || y >= int(lm.height)) continue;
                    const glm::vec2 centre(float(x) + 0.5f, float(y) + 0.5f);
                    const glm::vec2 bc = closestBarycentric(centre, c[0], c[1], c[2]);
                    const glm::vec2 q = c[0] * (1.0f - bc.x - bc.y) + c[1] * bc.x + c[2] * bc.y;
                    const float dist = glm::length(q - centre);
                    TexelOwner& o = owner[size_t(y) * lm.width + size_t(x)];
                    if (dist <= 0.75f && dist < o.distance) o = {dist, pi, t};
                }
        }
    }
    // The covered texels, and of them this shard's runs (BakeOptions::shard, kShardRun).
    const uint32_t shards = std::max(options.shards, 1u);
    if (options.shard >= shards)
        return fail(ErrorCode::InvalidInput, "lightmap: shard " +
                                                 std::to_string(options.shard + 1) + " of " +
                                                 std::to_string(shards) + " does not exist");
    std::vector<uint32_t> work;
    uint32_t covered = 0;
    for (uint32_t i = 0; i < texels; ++i)
        if (owner[i].distance < 1e29f && (covered++ / kShardRun) % shards == options.shard)
            work.push_back(i);

    const LightmapFit fit = lightmapFit(settings.lobes, lm.sharpness);
    lm.unit = fit.unit;
    const Context ctx{scene, tracer, allLights, environment, std::max(settings.bounces, 0)};
    const int samples = std::max(settings.samples, 1);
    const int strata = std::max(1, int(std::sqrt(double(samples))));
    std::atomic<size_t> next{0}, done{0};
    std::atomic<uint64_t> totalRays{0};
    const size_t chunk = 64;
    auto worker = [&]() {
        uint64_t rays = 0;
        std::vector<glm::dvec3> proj(lm.axes.size()), irr(fit.normals.size());
        for (;;) {
            const size_t begin = next.fetch_add(chunk);
            if (begin >= work.size()) break;
            const size_t end = std::min(work.size(), begin + chunk);
            for (size_t w = begin; w < end; ++w) {
                const uint32_t texel = work[w];
                const TexelOwner& o = owner[texel];
                const Part& part = parts[o.part];
                const Primitive& p = *part.prim;
                const uint32_t x = texel % lm.width, y = texel / lm.width;
                const glm::vec4 rect = atlas.rects[part.node];
                glm::vec2 c[3];
                for (int k = 0; k < 3; ++k)
                    c[k] =
                        (p.vertices[p.indices[3 * o.triangle + uint32_t(k)]].uv1 * glm::vec2(rect) +
                         glm::vec2(rect.z, rect.w)) *
                        glm::vec2(lm.width, lm.height);
                Rng rng(uint64_t(options.seed) * 0x9E3779B97F4A7C15ull + texel);
                std::fill(proj.begin(), proj.end(), glm::dvec3(0.0));
                std::fill(irr.begin(), irr.end(), glm::dvec3(0.0));
                for (int s = 0; s < samples; ++s) {
                    // A point jittered over the texel, clamped onto the triangle.
                    const glm::vec2 jitter(float(x) + rng.uniform(), float(y) + rng.uniform());
                    const glm::vec2 bc = closestBarycentric(jitter, c[0], c[1], c[2]);
                    const Surface surf = surfaceAt(part, o.triangle, bc.x, bc.y);
                    Frame f = surf.frame;
                    glm::vec3 ng = surf.geometricNormal;
                    if (glm::dot(ng, f.n) < 0.0f) ng = -ng;
                    const glm::vec3 origin = surf.position + ng * tracer.epsilon();
                    // Stratified uniform hemisphere direction (pdf 1 / 2π).
                    const int si = s % (strata * strata);
                    const float u1 = (float(si % strata) + rng.uniform()) / float(strata);
                    const float u2 = (float(si / strata) + rng.uniform()) / float(strata);
                    const float z = u1, r = std::sqrt(std::max(0.0f, 1.0f - z * z)),
                                phi = 2.0f * kPi * u2;
                    const glm::vec3 local(r * std::cos(phi), r * std::sin(phi), z);
                    const glm::vec3 dir = f.toWorld(local);
                    glm::vec3 L(0.0f);
                    if (glm::dot(dir, ng) > 0.0f)
                        L = radiance(ctx, origin, dir, ctx.bounces, rng, rays);
                    const double weight = 2.0 * double(kPi);
                    for (size_t k = 0; k < lm.axes.size(); ++k)
                        proj[k] += glm::dvec3(L) *
                                   (weight * std::exp(double(lm.sharpness) *
                                                      (double(glm::dot(lm.axes[k], local)) - 1.0)));
                    for (size_t j = 0; j < fit.normals.size(); ++j)
                        irr[j] +=
                            glm::dvec3(L) *
                            (weight * double(std::max(0.0f, glm::dot(fit.normals[j], local))));
                    // Baked lights: their direct light at the texel as deltas of illuminance.
                    for (const GpuLight& g : bakedLights) {
                        const LightSample ls = sampleLight(g, origin, rng);
                        const glm::vec3 d(glm::dot(ls.direction, f.t), glm::dot(ls.direction, f.b),
                                          glm::dot(ls.direction, f.n));
                        if (d.z <= 0.0f || glm::dot(ls.direction, ng) <= 0.0f ||
                            ls.illuminance == glm::vec3(0.0f))
                            continue;
                        if (tracer.occluded(origin, ls.direction,
                                            std::isinf(ls.distance)
                                                ? INFINITY
                                                : ls.distance * (1.0f - 1e-4f) - tracer.epsilon(),
                                            rays))
                            continue;
                        for (size_t k = 0; k < lm.axes.size(); ++k)
                            proj[k] += glm::dvec3(ls.illuminance) *
                                       std::exp(double(lm.sharpness) *
                                                (double(glm::dot(lm.axes[k], d)) - 1.0));
                        for (size_t j = 0; j < fit.normals.size(); ++j)
                            irr[j] += glm::dvec3(ls.illuminance) *
                                      double(std::max(0.0f, glm::dot(fit.normals[j], d)));
                    }
                }
                for (auto& v : proj) v /= double(samples);
                for (auto& v : irr) v /= double(samples);
                const std::vector<glm::vec3> amplitudes = fit.solve(proj, irr);
                for (size_t k = 0; k < amplitudes.size(); ++k) lm.lobes[k][texel] = amplitudes[k];
                lm.coverage[texel] = 1;
            }
            done.fetch_add(end - begin);
        }
        totalRays.fetch_add(rays);
    };
    const unsigned threads =
        options.threads ? options.threads : std::max(1u, std::thread::hardware_concurrency());
    std::vector<std::thread> pool;
    for (unsigned t = 0; t < threads; ++t) pool.emplace_back(worker);
    if (options.progress) {
        while (done.load() < work.size()) {
            std::this_thread::sleep_for(std::chrono::milliseconds(500));
            const double fraction = double(done.load()) / double(work.size());
            const double elapsed =
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            options.progress(fraction,
                             fraction > 0.0 ? elapsed * (1.0 - fraction) / fraction : 0.0);
        }
    }
    for (auto& t : pool) t.join();

    if (shards == 1) dilateLightmap(lm);  // a shard's part is dilated when merged
    if (stats) {
        stats->seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        stats->rays = totalRays.load();
        stats->texels = static_cast<uint32_t>(work.size());
        stats->covered = covered;
    }
    return lm;
}

}  // namespace rg::bake

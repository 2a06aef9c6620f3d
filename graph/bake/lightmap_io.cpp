// The lightmap's EXR file, its cache key and its CPU evaluation.
#include <cstdio>
#include <filesystem>
#include <unistd.h>
#include <cstring>
#include <sstream>

#include "bake/lightmap.h"
#include "core/hash.h"
#include "scene/scene_detail.h"
#include "image/image.h"
#include "lighting/sg.h"
#include "core/temp_path.h"

namespace rg::bake {

namespace {

// Bumped whenever the baker's output for the same input changes.
constexpr uint32_t kBakerVersion = 2;

}  // namespace

std::string lightmapKey(const Scene& scene, const LightmapSettings& s) {
    ContentHash h;
    h.pod(kBakerVersion);
    h.pod(s.density), h.pod(s.lobes), h.pod(s.samples), h.pod(s.bounces), h.pod(s.maxSize);
    for (const Node& n : scene.nodes) {
        h.pod(n.world), h.pod(n.mesh);
        if (n.mesh < 0 || size_t(n.mesh) >= scene.meshes.size()) continue;
        for (const auto& p : scene.meshes[size_t(n.mesh)].primitives) {
            h.pod(p.material), h.pod(p.lightmapUv);
            h.bytes(p.vertices.data(), p.vertices.size() * sizeof(Vertex));
            h.bytes(p.indices.data(), p.indices.size() * sizeof(uint32_t));
        }
    }
    for (const Material& m : scene.materials) {
        h.str(m.model);
        h.pod(m.baseColor), h.pod(m.metalMask), h.pod(m.emissive), h.pod(m.diffuseColor),
            h.pod(m.doubleSided);
        if (m.emissiveEv) h.pod(m.emissiveEc);  // (only then: older scenes keep their keys)
        for (const TextureRef* t : {&m.baseColorTex, &m.emissiveTex, &m.metallicRoughnessTex}) {
            h.pod(t->texCoord), h.pod(t->transform);
            if (t->image >= 0 && size_t(t->image) < scene.images.size()) {
                const auto& px = scene.images[size_t(t->image)].pixels;
                h.pod(px.width), h.pod(px.height),
                    h.bytes(px.pixels.data(), px.pixels.size() * sizeof(float));
            }
        }
    }
    for (const Light& l : scene.lights) {
        h.pod(l.type), h.pod(l.position), h.pod(l.direction), h.pod(l.up), h.pod(l.color),
            h.pod(l.temperatureK), h.pod(l.intensity);
        h.str(l.unit), h.pod(l.radius), h.pod(l.width), h.pod(l.height), h.pod(l.length),
            h.pod(l.innerAngle), h.pod(l.outerAngle);
        h.pod(l.range), h.pod(l.exactCone), h.pod(l.sunAngularRadius), h.pod(l.baked), h.str(l.ies),
            h.pod(l.cone), h.pod(l.daylight);
    }
    if (scene.environment) {
        const Environment& e = *scene.environment;
        h.str(e.kind), h.pod(e.color), h.pod(e.intensity), h.pod(e.rotation), h.pod(e.turbidity);
        if (!e.file.empty())
            if (auto bytes = scene_detail::readFile(e.file)) h.bytes(bytes->data(), bytes->size());
    }
    return h.hex();
}

glm::vec3 lightmapIrradiance(const Lightmap& lm, uint32_t x, uint32_t y, glm::vec3 n) {
    glm::vec3 e(0.0f);
    const size_t i = size_t(y) * lm.width + x;
    for (size_t k = 0; k < lm.axes.size(); ++k)
        e += lighting::irradiance({lm.axes[k], lm.sharpness, lm.lobes[k][i]}, n);
    return e;
}

glm::vec3 lightmapSpecular(const Lightmap& lm, size_t texel, glm::vec3 N, glm::vec3 V,
                           float linearRoughness) {
    // The GGX shape 1 / (1 + t)², t = tan²θ_h / α², as Σ c_i e^{−b_i t} (lib/lightmap.glsl).
    constexpr float kB[3] = {0.191f, 0.909f, 2.776f}, kC[3] = {0.0612f, 0.4119f, 0.5163f};
    const float alpha = std::max(linearRoughness * linearRoughness, 0.02f);
    const glm::vec3 R = glm::reflect(-V, N);
    const float warp = 2.0f / (alpha * alpha) / (4.0f * std::max(glm::dot(N, V), 0.05f));
    glm::vec3 ld(0.0f);
    float one = 0.0f;
    for (size_t k = 0; k < lm.axes.size(); ++k) {
        float w = 0.0f;
        for (int i = 0; i < 3; ++i)
            w += kC[i] * lighting::innerProduct({lm.axes[k], lm.sharpness, glm::vec3(1.0f)},
                                                {R, kB[i] * warp, glm::vec3(1.0f)})
                             .x;
        ld += lm.lobes[k][texel] * w;
        one += (k < lm.unit.size() ? lm.unit[k] : 0.0f) * w;
    }
    return ld / std::max(one, 1e-6f);
}

Result<void> writeLightmapExr(const std::string& path, const Lightmap& lm,
                              const LightmapPart* part) {
    // A whole lightmap: the atlas, a layer per lobe and the coverage. A part: only its texels, in
    // rows of kShardRun, their atlas indices in layer "texel" (hi × 65536 + lo, exact as floats),
    // so N parts hold one atlas's worth between them, not N.
    std::vector<uint32_t> texels;
    if (part)
        for (uint32_t i = 0; i < lm.coverage.size(); ++i)
            if (lm.coverage[i]) texels.push_back(i);
    const uint32_t width = part ? kShardRun : lm.width;
    const uint32_t height =
        part ? std::max<uint32_t>(1, uint32_t((texels.size() + kShardRun - 1) / kShardRun))
             : lm.height;
    std::vector<ImageLayer> layers;
    for (size_t k = 0; k < lm.lobes.size(); ++k) {
        ImageLayer layer{"sg" + std::to_string(k), {"R", "G", "B"}, Image(width, height, 3)};
        if (part)
            for (size_t j = 0; j < texels.size(); ++j)
                for (int c = 0; c < 3; ++c)
                    layer.image.pixels[j * 3 + size_t(c)] = lm.lobes[k][texels[j]][c];
        else
            for (size_t i = 0; i < lm.lobes[k].size(); ++i)
                for (int c = 0; c < 3; ++c)
                    layer.image.pixels[i * 3 + size_t(c)] = lm.lobes[k][i][c];
        layers.push_back(std::move(layer));
    }
    if (part) {
        ImageLayer index{"texel", {"hi", "lo"}, Image(width, height, 2)};
        std::fill(index.image.pixels.begin(), index.image.pixels.end(), -1.0f);
        for (size_t j = 0; j < texels.size(); ++j) {
            index.image.pixels[j * 2] = float(texels[j] >> 16);
            index.image.pixels[j * 2 + 1] = float(texels[j] & 0xffffu);
        }
        layers.push_back(std::move(index));
    } else {
        ImageLayer coverage{"coverage", {"Y"}, Image(lm.width, lm.height, 1)};
        for (size_t i = 0; i < lm.coverage.size(); ++i)
            coverage.image.pixels[i] = lm.coverage[i] ? 1.0f : 0.0f;
        layers.push_back(std::move(coverage));
    }
    ExrWriteOptions o;
    o.pixelType = ExrPixelType::Float;
    std::ostringstream axes;
    for (size_t k = 0; k < lm.axes.size(); ++k)
        axes << (k ? "; " : "") << lm.axes[k].x << ' ' << lm.axes[k].y << ' ' << lm.axes[k].z;
    o.metadata["rgraph.lightmap.axes"] = axes.str();
    o.metadata["rgraph.lightmap.key"] = lm.key;
    o.metadata["rgraph.lightmap.space"] = "tangent";
    std::ostringstream unit;
    for (size_t k = 0; k < lm.unit.size(); ++k) unit << (k ? " " : "") << lm.unit[k];
    o.metadata["rgraph.lightmap.unit"] = unit.str();
    o.ints["rgraph.lightmap.lobes"] = static_cast<int>(lm.axes.size());
    o.floats["rgraph.lightmap.sharpness"] = lm.sharpness;
    o.floats["rgraph.lightmap.density"] = lm.density;
    if (part) {
        o.ints["rgraph.lightmap.shard"] = static_cast<int>(part->shard + 1);
        o.ints["rgraph.lightmap.shards"] = static_cast<int>(part->shards);
        o.ints["rgraph.lightmap.texels"] = static_cast<int>(part->texels);
        o.ints["rgraph.lightmap.covered"] = static_cast<int>(part->covered);
        o.ints["rgraph.lightmap.width"] = static_cast<int>(lm.width);
        o.ints["rgraph.lightmap.height"] = static_cast<int>(lm.height);
    }
    // Beside the target under a name of this writer's own, then renamed over it.
    const std::string tmp = tempPathBeside(path);
    if (auto r = writeExr(tmp, layers, o); !r) {
        std::error_code ec;
        std::filesystem::remove(tmp, ec);
        return r;
    }
    std::error_code ec;
    std::filesystem::rename(tmp, path, ec);
    if (ec) {
        std::filesystem::remove(tmp, ec);
        return fail(ErrorCode::Io, "cannot write '" + path + "': " + ec.message());
    }
    return {};
}

Result<Lightmap> readLightmapExr(const std::string& path, LightmapPart* part) {
    auto file = readExr(path);
    if (!file) return std::unexpected(file.error());
    auto bad = [&](const std::string& why) {
        return fail(ErrorCode::InvalidInput, path + ": not an rgraph lightmap: " + why);
    };
    Lightmap lm;
    auto lobes = file->ints.find("rgraph.lightmap.lobes");
    auto sharp = file->floats.find("rgraph.lightmap.sharpness");
    auto axesAttr = file->metadata.find("rgraph.lightmap.axes");
    if (lobes == file->ints.end() || sharp == file->floats.end() ||
        axesAttr == file->metadata.end())
        return bad("its header lacks rgraph.lightmap.lobes, .sharpness or .axes");
    if (lobes->second < 1 || lobes->second > 64)
        return bad("rgraph.lightmap.lobes is " + std::to_string(lobes->second));
    lm.sharpness = static_cast<float>(sharp->second);
    const auto shard = file->ints.find("rgraph.lightmap.shard"),
               shards = file->ints.find("rgraph.lightmap.shards");
    if (shard != file->ints.end() && !part)
        return fail(ErrorCode::InvalidInput,
                    path + ": is shard " + std::to_string(shard->second) + " of " +
                        (shards != file->ints.end() ? std::to_string(shards->second) : "?") +
                        " of a sharded bake, not a whole lightmap: merge the shards with `rgraph "
                        "bake --merge PART...`");
    if (part) {
        auto get = [&](const char* name) {
            auto it = file->ints.find(name);
            return it == file->ints.end() ? -1 : it->second;
        };
        const int k = get("rgraph.lightmap.shard"), n = get("rgraph.lightmap.shards"),
                  texels = get("rgraph.lightmap.texels"), covered = get("rgraph.lightmap.covered");
        if (k < 1 || n < 1 || k > n || texels < 0 || covered < texels)
            return bad(
                "not a shard of a sharded bake (its header lacks a valid "
                "rgraph.lightmap.shard, .shards, .texels or .covered)");
        *part = {uint32_t(k - 1), uint32_t(n), uint32_t(texels), uint32_t(covered)};
    }
    if (auto d = file->floats.find("rgraph.lightmap.density"); d != file->floats.end())
        lm.density = static_cast<float>(d->second);
    if (auto k = file->metadata.find("rgraph.lightmap.key"); k != file->metadata.end())
        lm.key = k->second;
    std::istringstream axes(axesAttr->second);
    for (int k = 0; k < lobes->second; ++k) {
        glm::vec3 a;
        char sep = ';';
        if (k > 0 && !(axes >> sep))
            return bad("rgraph.lightmap.axes has fewer than " + std::to_string(lobes->second) +
                       " axes");
        if (sep != ';' || !(axes >> a.x >> a.y >> a.z))
            return bad("rgraph.lightmap.axes is not 'x y z; x y z; ...'");
        lm.axes.push_back(a);
    }
    if (auto u = file->metadata.find("rgraph.lightmap.unit"); u != file->metadata.end()) {
        std::istringstream in(u->second);
        float v = 0.0f;
        while (in >> v) lm.unit.push_back(v);
    }
    if (lm.unit.size() != lm.axes.size())
        return bad("rgraph.lightmap.unit does not hold one amplitude per lobe");
    auto layer = [&](const std::string& name) -> const ImageLayer* {
        for (const auto& l : file->layers)
            if (l.name == name) return &l;
        return nullptr;
    };
    if (part) {  // a part's texels into the atlas they came from (writeLightmapExr)
        const int w =
            file->ints.count("rgraph.lightmap.width") ? file->ints["rgraph.lightmap.width"] : 0;
        const int h =
            file->ints.count("rgraph.lightmap.height") ? file->ints["rgraph.lightmap.height"] : 0;
        const ImageLayer* index = layer("texel");
        if (w < 1 || h < 1 || w > 65536 || h > 65536 || !index || index->image.channels < 2)
            return bad(
                "a shard without its atlas size (rgraph.lightmap.width, .height) or its "
                "texel layer");
        lm.width = uint32_t(w), lm.height = uint32_t(h);
        const size_t atlas = size_t(lm.width) * lm.height, rows = index->image.pixels.size() / 2;
        if (rows < part->texels)
            return bad("its texel layer holds fewer texels than its header says");
        lm.lobes.assign(size_t(lobes->second), std::vector<glm::vec3>(atlas, glm::vec3(0.0f)));
        lm.coverage.assign(atlas, 0);
        std::vector<const ImageLayer*> sg;
        for (int k = 0; k < lobes->second; ++k) {
            sg.push_back(layer("sg" + std::to_string(k)));
            if (!sg.back() || sg.back()->image.channels < 3 ||
                sg.back()->image.pixels.size() / sg.back()->image.channels != rows)
                return bad("no RGB layer sg" + std::to_string(k) + " beside its texel layer");
        }
        for (size_t j = 0; j < part->texels; ++j) {
            const float hi = index->image.pixels[j * 2], lo = index->image.pixels[j * 2 + 1];
            const bool valid = hi >= 0.0f && hi < 65536.0f && lo >= 0.0f && lo < 65536.0f;
            const size_t i = valid ? size_t(hi) * 65536u + size_t(lo) : atlas;
            if (i >= atlas || lm.coverage[i])
                return bad("its texel layer's entry " + std::to_string(j) +
                           " names a texel outside the atlas, or one named before");
            lm.coverage[i] = 1;
            for (int k = 0; k < lobes->second; ++k)
                for (uint32_t c = 0; c < 3; ++c)
                    lm.lobes[size_t(k)][i][int(c)] =
                        sg[size_t(k)]->image.pixels[j * sg[size_t(k)]->image.channels + c];
        }
        return lm;
    }
    for (int k = 0; k < lobes->second; ++k) {
        const ImageLayer* l = layer("sg" + std::to_string(k));
        if (!l || l->image.channels < 3) return bad("no RGB layer sg" + std::to_string(k));
        if (k == 0) lm.width = l->image.width, lm.height = l->image.height;
        std::vector<glm::vec3> v(size_t(lm.width) * lm.height);
        for (size_t i = 0; i < v.size(); ++i)
            for (uint32_t c = 0; c < 3; ++c)
                v[i][int(c)] = l->image.pixels[i * l->image.channels + c];
        lm.lobes.push_back(std::move(v));
    }
    lm.coverage.assign(size_t(lm.width) * lm.height, 1);
    if (const ImageLayer* c = layer("coverage"))
        for (size_t i = 0; i < lm.coverage.size() && i < c->image.pixels.size(); ++i)
            lm.coverage[i] = c->image.pixels[i] > 0.5f;
    return lm;
}

namespace {

// options.bake with progress and ETA on stderr (unless quiet); the figures are printed unless the
// caller takes them (options.stats), which is then filled.
Result<Lightmap> bakeWithProgress(const Scene& scene, const LightmapAtlas& atlas,
                                  const PrepareOptions& options, BakeOptions bo, BakeStats& stats) {
    const LightmapSettings& settings = *scene.lightmap;
    bo.threads = options.threads;
    const bool tty = isatty(fileno(stderr));
    if (!options.quiet) {
        std::fprintf(stderr,
                     "rgraph: baking lightmap '%s'%s: %ux%u texels, %d lobes, %d paths per texel, "
                     "%d bounces\n",
                     settings.name.c_str(),
                     bo.shards > 1 ? (" shard " + std::to_string(bo.shard + 1) + "/" +
                                      std::to_string(bo.shards))
                                         .c_str()
                                   : "",
                     atlas.width, atlas.height, settings.lobes, settings.samples, settings.bounces);
        bo.progress = [tty, last = -1](double fraction, double left) mutable {
            const int percent = static_cast<int>(fraction * 100.0);
            if (!tty && percent / 10 == last / 10) return;
            last = percent;
            std::fprintf(stderr,
                         tty ? "\rrgraph: baking %3d %%, %.0f s left   "
                             : "rgraph: baking %3d %%, %.0f s left\n",
                         percent, left);
        };
    }
    auto baked = options.bake(scene, atlas, settings, bo, &stats);
    if (!options.quiet && tty) std::fprintf(stderr, "\n");
    if (!baked) return std::unexpected(baked.error());
    if (options.stats) *options.stats = stats;
    if (!options.quiet && !options.stats)  // a caller that takes the figures prints them
        std::fprintf(stderr, "rgraph: baked %u texels in %.1f s (%.2f M rays/s)\n", stats.texels,
                     stats.seconds,
                     stats.seconds > 0 ? double(stats.rays) / stats.seconds * 1e-6 : 0.0);
    return baked;
}

}  // namespace

Result<void> prepareLightmap(Scene& scene, const PrepareOptions& options) {
    if (!scene.lightmap) return {};
    const LightmapSettings& settings = *scene.lightmap;
    auto atlas = packLightmap(scene, settings);
    if (!atlas) return std::unexpected(atlas.error());
    applyAtlas(scene, *atlas);
    const std::string key = lightmapKey(scene, settings);
    const std::string path = options.cacheDir + "/" + key + ".exr";
    if (options.path) *options.path = path;
    std::error_code ec;
    if (!options.rebake && std::filesystem::is_regular_file(path, ec)) {
        auto cached = readLightmapExr(path);
        if (cached && cached->key == key && cached->width == atlas->width &&
            cached->height == atlas->height && int(cached->axes.size()) == settings.lobes) {
            if (options.fromCache) *options.fromCache = true;
            scene.bakedLightmap = std::make_shared<const Lightmap>(std::move(*cached));
            return {};
        }
    }
    if (options.fromCache) *options.fromCache = false;
    if (!options.bake)
        return fail(ErrorCode::NotFound,
                    "not baked for this scene (no " + key +
                        ".exr in the lightmap cache): bake it with "
                        "`rgraph bake SCENE`, or render with a host that links the baker");
    BakeStats stats;
    auto baked = bakeWithProgress(scene, *atlas, options, BakeOptions{}, stats);
    if (!baked) return std::unexpected(baked.error());
    baked->key = key;
    std::filesystem::create_directories(options.cacheDir, ec);
    if (auto r = writeLightmapExr(path, *baked); !r) return std::unexpected(r.error());
    scene.bakedLightmap = std::make_shared<const Lightmap>(std::move(*baked));
    return {};
}

Result<LightmapShard> prepareLightmapShard(Scene& scene, const PrepareOptions& options,
                                           uint32_t shard, uint32_t shards) {
    if (!scene.lightmap)
        return fail(ErrorCode::InvalidInput, "the scene declares no scene.lightmap");
    if (shards < 1 || shard >= shards)
        return fail(ErrorCode::InvalidInput, "shard " + std::to_string(shard + 1) + " of " +
                                                 std::to_string(shards) + " does not exist");
    const LightmapSettings& settings = *scene.lightmap;
    auto atlas = packLightmap(scene, settings);
    if (!atlas) return std::unexpected(atlas.error());
    applyAtlas(scene, *atlas);
    const std::string key = lightmapKey(scene, settings);
    const std::string path = options.cacheDir + "/" + key + ".shard-" + std::to_string(shard + 1) +
                             "-of-" + std::to_string(shards) + ".exr";
    if (options.path) *options.path = path;
    std::error_code ec;
    if (!options.rebake && std::filesystem::is_regular_file(path, ec)) {
        LightmapShard cached;
        auto lm = readLightmapExr(path, &cached.part);
        if (lm && lm->key == key && lm->width == atlas->width && lm->height == atlas->height &&
            int(lm->axes.size()) == settings.lobes && cached.part.shard == shard &&
            cached.part.shards == shards) {
            if (options.fromCache) *options.fromCache = true;
            cached.lightmap = std::move(*lm);
            return cached;
        }
    }
    if (options.fromCache) *options.fromCache = false;
    if (!options.bake) return fail(ErrorCode::NotFound, "no baker to bake a shard with");
    BakeOptions bo;
    bo.shard = shard;
    bo.shards = shards;
    BakeStats stats;
    auto baked = bakeWithProgress(scene, *atlas, options, bo, stats);
    if (!baked) return std::unexpected(baked.error());
    baked->key = key;
    LightmapShard result{std::move(*baked), {shard, shards, stats.texels, stats.covered}};
    std::filesystem::create_directories(options.cacheDir, ec);
    if (auto r = writeLightmapExr(path, result.lightmap, &result.part); !r)
        return std::unexpected(r.error());
    return result;
}

std::vector<glm::vec3> lightmapAxes(int lobes) { return lighting::goldenSpiralAxes(lobes, true); }

LightmapFit lightmapFit(int lobes, float sharpness) {
    LightmapFit f;
    f.axes = lightmapAxes(lobes);
    f.sharpness = sharpness;
    // The surface normal itself first, weighing as much as all the others together: an unmapped
    // surface — most of a lightmap — gets its irradiance nearly exact; then normals within 70°.
    f.normals.push_back(glm::vec3(0.0f, 0.0f, 1.0f));
    for (const auto& n : lighting::goldenSpiralAxes(48, true))
        if (n.z >= 0.34f) f.normals.push_back(n);
    const size_t N = f.axes.size(), J = f.normals.size();
    f.weights.assign(J, 1.0);
    f.weights[0] = double(J - 1);
    f.irradiance.resize(J * N);
    for (size_t j = 0; j < J; ++j)
        for (size_t k = 0; k < N; ++k)
            f.irradiance[j * N + k] =
                lighting::irradiance({f.axes[k], sharpness, glm::vec3(1.0f)}, f.normals[j]).x;
    const std::vector<double> radiance = lighting::basisGram(f.axes, sharpness, true);
    f.gram.assign(N * N, 0.0);
    double traceIrr = 0.0, traceRad = 0.0;
    for (size_t i = 0; i < N; ++i) {
        for (size_t k = 0; k < N; ++k)
            for (size_t j = 0; j < J; ++j)
                f.gram[i * N + k] +=
                    f.weights[j] * f.irradiance[j * N + i] * f.irradiance[j * N + k];
        traceIrr += f.gram[i * N + i], traceRad += radiance[i * N + i];
    }
    // The radiance term at a tenth of the irradiance term's weight: enough to keep the lobes a
    // plausible radiance (smooth, where the light comes from), little enough not to pull the
    // irradiance off (tests/unit/test_lightmap.cpp measures both).
    f.radianceWeight = 0.1 * traceIrr / traceRad;
    for (size_t i = 0; i < N * N; ++i) f.gram[i] += f.radianceWeight * radiance[i];
    // A uniform 1 nit over the hemisphere, by quadrature.
    std::vector<glm::dvec3> proj(N, glm::dvec3(0.0)), irr(J, glm::dvec3(0.0));
    const std::vector<glm::vec3> dirs = lighting::goldenSpiralAxes(1 << 14);
    const double dw = 4.0 * 3.14159265358979323846 / double(dirs.size());
    for (const auto& d : dirs) {
        if (d.z <= 0.0f) continue;
        for (size_t k = 0; k < N; ++k)
            proj[k] += glm::dvec3(
                dw * std::exp(double(sharpness) * (double(glm::dot(f.axes[k], d)) - 1.0)));
        for (size_t j = 0; j < J; ++j)
            irr[j] += glm::dvec3(dw * double(std::max(0.0f, glm::dot(f.normals[j], d))));
    }
    for (const glm::vec3& a : f.solve(proj, irr)) f.unit.push_back(a.x);
    return f;
}

std::vector<glm::vec3> LightmapFit::solve(const std::vector<glm::dvec3>& projections,
                                          const std::vector<glm::dvec3>& irradiances) const {
    const size_t N = axes.size(), J = normals.size();
    std::vector<glm::dvec3> atb(N, glm::dvec3(0.0));
    for (size_t k = 0; k < N; ++k) {
        atb[k] = radianceWeight * projections[k];
        for (size_t j = 0; j < J; ++j)
            atb[k] += weights[j] * irradiance[j * N + k] * irradiances[j];
    }
    return lighting::fitNonNegative(gram, atb);
}

float lightmapSharpness(int lobes) {
    return lighting::basisSharpness(lightmapAxes(lobes)) * kLightmapSharpnessScale;
}

}  // namespace rg::bake

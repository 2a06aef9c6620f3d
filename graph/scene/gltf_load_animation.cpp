// glTF animations (glTF 2.0 §3.11): the chosen animation's samplers and channels read and checked,
// and the Scene nodes under the nodes it moves made dynamic, placed each frame by
// Animation::world — translation, rotation and scale keyframes, STEP, LINEAR (rotations slerped)
// or CUBICSPLINE, looping over the animation's duration. Morph weights are not animated (the
// meshes keep the weights of the load), nor are skins (posed once at load).
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <memory>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include "core/names.h"
#include "gltf_load_detail.h"
#include "scene_detail.h"
#include "tinygltf.h"

namespace rg {

namespace {

constexpr size_t kMaxKeys = size_t(1) << 22;  // keys in all of an animation's samplers

glm::quat quatOf(glm::vec4 v) { return glm::quat(v.w, v.x, v.y, v.z); }
glm::vec4 vec4Of(glm::quat q) { return glm::vec4(q.x, q.y, q.z, q.w); }

}  // namespace

glm::vec4 Animation::sample(size_t s, float t) const {
    const Sampler& sm = samplers[s];
    const bool cubic = sm.interpolation == Interpolation::CubicSpline;
    auto value = [&](size_t k) { return sm.values[cubic ? 3 * k + 1 : k]; };
    const size_t n = sm.times.size();
    if (t <= sm.times.front() || n == 1) return value(0);
    if (t >= sm.times.back()) return value(n - 1);
    // The key at or before t (times ascend).
    const size_t k =
        size_t(std::upper_bound(sm.times.begin(), sm.times.end(), t) - sm.times.begin()) - 1;
    const float t0 = sm.times[k], t1 = sm.times[k + 1], span = t1 - t0;
    const float u = span > 0.0f ? (t - t0) / span : 0.0f;
    glm::vec4 v;
    switch (sm.interpolation) {
        case Interpolation::Step:
            return value(k);
        case Interpolation::Linear:
            if (sm.rotation)
                return vec4Of(
                    glm::normalize(glm::slerp(quatOf(value(k)), quatOf(value(k + 1)), u)));
            return glm::mix(value(k), value(k + 1), u);
        case Interpolation::CubicSpline: {
            // §3.11's Hermite spline: the key's out-tangent and the next key's in-tangent, scaled
            // by the span.
            const float u2 = u * u, u3 = u2 * u;
            v = (2 * u3 - 3 * u2 + 1) * value(k) + (u3 - 2 * u2 + u) * span * sm.values[3 * k + 2] +
                (-2 * u3 + 3 * u2) * value(k + 1) + (u3 - u2) * span * sm.values[3 * (k + 1)];
            if (sm.rotation) v = vec4Of(glm::normalize(quatOf(v)));
            return v;
        }
    }
    return value(k);
}

glm::mat4 Animation::world(size_t node, double seconds) const {
    const float t = duration > 0.0f
                        ? static_cast<float>(std::fmod(std::max(seconds, 0.0), double(duration)))
                        : 0.0f;
    glm::mat4 m(1.0f);
    // Up the parents (the loader checked the hierarchy has no cycle; the count bounds it anyway),
    // each local on the left.
    size_t steps = 0;
    for (int32_t n = static_cast<int32_t>(node);
         n >= 0 && size_t(n) < nodes.size() && steps++ <= nodes.size();
         n = nodes[size_t(n)].parent) {
        const GltfNode& g = nodes[size_t(n)];
        glm::mat4 local;
        if (g.matrix) {
            local = *g.matrix;
        } else {
            const glm::vec3 tr =
                g.sampler[0] >= 0 ? glm::vec3(sample(size_t(g.sampler[0]), t)) : g.translation;
            const glm::vec4 r = g.sampler[1] >= 0 ? sample(size_t(g.sampler[1]), t) : g.rotation;
            const glm::vec3 sc =
                g.sampler[2] >= 0 ? glm::vec3(sample(size_t(g.sampler[2]), t)) : g.scale;
            local = scene_detail::trs(tr, glm::normalize(quatOf(r)), sc);
        }
        m = local * m;
    }
    return m;
}

namespace gltf_load {

Result<Animation::Sampler> Loader::animationSampler(const std::string& where,
                                                    const tinygltf::AnimationSampler& s,
                                                    const std::string& path) {
    Animation::Sampler out;
    out.rotation = path == "rotation";
    if (s.interpolation == "STEP")
        out.interpolation = Animation::Interpolation::Step;
    else if (s.interpolation == "CUBICSPLINE")
        out.interpolation = Animation::Interpolation::CubicSpline;
    else if (s.interpolation == "LINEAR" || s.interpolation.empty())
        out.interpolation = Animation::Interpolation::Linear;
    else
        return error(ErrorCode::InvalidInput, where + ": interpolation '" + s.interpolation +
                                                  "': expected LINEAR, STEP or CUBICSPLINE");
    RG_TRY(out.times, readFloats(where, "input", s.input, TINYGLTF_TYPE_SCALAR));
    if (out.times.empty() || out.times.size() > kMaxKeys)
        return error(ErrorCode::InvalidInput,
                     where + ": input has " + std::to_string(out.times.size()) +
                         " keys (expected 1 to " + std::to_string(kMaxKeys) + ")");
    for (size_t k = 0; k < out.times.size(); ++k)
        if (out.times[k] < 0.0f || (k > 0 && out.times[k] <= out.times[k - 1]))
            return error(ErrorCode::InvalidInput,
                         where + ": input key " + std::to_string(k) + " is " + fmt(out.times[k]) +
                             (out.times[k] < 0.0f
                                  ? ", before 0"
                                  : ", not after the key before (" + fmt(out.times[k - 1]) + ")"));
    const int type = out.rotation ? TINYGLTF_TYPE_VEC4 : TINYGLTF_TYPE_VEC3;
    std::vector<float> values;
    RG_TRY(values, readFloats(where, "output", s.output, type));
    const size_t comps = out.rotation ? 4 : 3;
    const size_t perKey = out.interpolation == Animation::Interpolation::CubicSpline ? 3 : 1;
    if (values.size() != out.times.size() * perKey * comps)
        return error(ErrorCode::InvalidInput,
                     where + ": output has " + std::to_string(values.size() / comps) +
                         " values for " + std::to_string(out.times.size()) + " keys (" +
                         (perKey == 3 ? "CUBICSPLINE: three a key" : "one a key") + ")");
    for (size_t i = 0; i < values.size() / comps; ++i) {
        glm::vec4 v(0.0f);
        for (size_t c = 0; c < comps; ++c) v[int(c)] = values[i * comps + c];
        out.values.push_back(v);
    }
    if (out.rotation)
        for (size_t k = 0; k < out.times.size(); ++k) {
            glm::vec4& q = out.values[perKey * k + (perKey == 3 ? 1 : 0)];
            if (glm::length(q) < 1e-6f)
                return error(ErrorCode::InvalidInput, where + ": output key " + std::to_string(k) +
                                                          " is not a rotation (a zero quaternion)");
            q = glm::normalize(q);  // slerp takes unit quaternions (quantised ones are near)
        }
    return out;
}

Result<void> Loader::animations() {
    if (options.animation == "none" || (model.animations.empty() && options.animation.empty()))
        return {};
    size_t chosen = 0;
    if (!options.animation.empty()) {
        std::vector<std::string> names;
        for (const auto& a : model.animations) names.push_back(a.name);
        const auto it = std::find(names.begin(), names.end(), options.animation);
        if (it == names.end())
            return error(ErrorCode::InvalidInput,
                         "no animation '" + options.animation + "' (the file has " +
                             std::to_string(names.size()) +
                             (names.empty() ? "" : ": " + joinQuoted(names)) + ")");
        chosen = size_t(it - names.begin());
    } else if (model.animations.size() > 1) {
        warn("the file has " + std::to_string(model.animations.size()) +
             " animations; the first plays (scene.gltf's `animation` picks another by name)");
    }
    const tinygltf::Animation& a = model.animations[chosen];
    const std::string where = named("animation", chosen, a.name);
    auto anim = std::make_shared<Animation>();
    anim->name = a.name;
    // Every glTF node the walk entered, with the node it entered it from and its rest transform
    // (a node the walk did not enter is never drawn).
    anim->nodes.resize(model.nodes.size());
    for (size_t i = 0; i < model.nodes.size(); ++i) {
        const auto& n = model.nodes[i];
        Animation::GltfNode& g = anim->nodes[i];
        if (i >= walkParent.size() || walkParent[i] == -2) continue;
        g.parent = walkParent[i];
        if (!n.matrix.empty()) {
            RG_TRY(g.matrix, localTransform(i));
            continue;
        }
        g.translation = vec3Of(n.translation, glm::vec3(0.0f));
        g.scale = vec3Of(n.scale, glm::vec3(1.0f));
        if (n.rotation.size() == 4)
            g.rotation = glm::vec4(float(n.rotation[0]), float(n.rotation[1]), float(n.rotation[2]),
                                   float(n.rotation[3]));
    }
    std::vector<bool> moved(model.nodes.size(), false);
    std::vector<std::array<bool, 3>> targeted(model.nodes.size(), {false, false, false});
    std::map<int, int32_t> read[3];  // glTF sampler -> Animation sampler, per path
    size_t keys = 0;
    bool weights = false;
    for (size_t c = 0; c < a.channels.size(); ++c) {
        const tinygltf::AnimationChannel& ch = a.channels[c];
        const std::string cw = where + ": channel " + std::to_string(c);
        if (ch.target_path == "weights") {
            weights = true;
            continue;
        }
        if (ch.target_node < 0) continue;  // an extension's target (KHR_animation_pointer)
        if (size_t(ch.target_node) >= model.nodes.size())
            return error(ErrorCode::InvalidInput,
                         cw + ": target node " + std::to_string(ch.target_node) +
                             " does not exist (" + std::to_string(model.nodes.size()) + " nodes)");
        const int path = ch.target_path == "translation" ? 0
                         : ch.target_path == "rotation"  ? 1
                         : ch.target_path == "scale"     ? 2
                                                         : -1;
        if (path < 0)
            return error(ErrorCode::InvalidInput,
                         cw + ": target path '" + ch.target_path +
                             "': expected translation, rotation, scale or weights");
        if (ch.sampler < 0 || size_t(ch.sampler) >= a.samplers.size())
            return error(ErrorCode::InvalidInput,
                         cw + ": sampler " + std::to_string(ch.sampler) + " does not exist (" +
                             std::to_string(a.samplers.size()) + " samplers)");
        const size_t target = size_t(ch.target_node);
        const std::string node = named("node", target, model.nodes[target].name);
        if (targeted[target][size_t(path)])
            return error(ErrorCode::InvalidInput,
                         cw + ": " + node + "'s " + ch.target_path +
                             " is targeted by an earlier channel too (glTF: once per animation)");
        targeted[target][size_t(path)] = true;
        Animation::GltfNode& g = anim->nodes[target];
        if (g.matrix)
            return error(ErrorCode::InvalidInput,
                         cw + ": " + node + " is given by a matrix, which glTF does not animate");
        // Each sampler read once (per path: the type of its outputs depends on it).
        auto known = read[path].find(ch.sampler);
        if (known == read[path].end()) {
            Animation::Sampler sampler;
            RG_TRY(sampler, animationSampler(where + ": sampler " + std::to_string(ch.sampler),
                                             a.samplers[size_t(ch.sampler)], ch.target_path));
            keys += sampler.times.size();
            if (keys > kMaxKeys)
                return error(
                    ErrorCode::InvalidInput,
                    where + ": more than " + std::to_string(kMaxKeys) + " keys in its samplers");
            anim->duration = std::max(anim->duration, sampler.times.back());
            known = read[path].emplace(ch.sampler, int32_t(anim->samplers.size())).first;
            anim->samplers.push_back(std::move(sampler));
        }
        g.sampler[path] = known->second;
        moved[target] = true;
    }
    if (weights)
        warn(where +
             " animates morph target weights, which rgraph does not play (the meshes keep "
             "the weights they load with)");
    if (anim->samplers.empty()) return {};
    // A node moves when it or a node above it is animated: worked out once per node, from the
    // highest node not yet known down.
    std::vector<int8_t> under(model.nodes.size(), -1);  // −1 not yet known
    auto movesUnder = [&](size_t n) {
        std::vector<size_t> chain;
        int32_t i = int32_t(n);
        for (; i >= 0 && under[size_t(i)] < 0 && chain.size() <= model.nodes.size();
             i = anim->nodes[size_t(i)].parent)
            chain.push_back(size_t(i));
        bool m = i >= 0 && under[size_t(i)] > 0;
        for (auto c = chain.rbegin(); c != chain.rend(); ++c) {
            m = m || moved[*c];
            under[*c] = m ? 1 : 0;
        }
        return under[n] > 0;
    };
    // A pose of one key (duration 0) moves nothing: its nodes take it and stand still.
    const bool still = anim->duration <= 0.0f;
    std::vector<bool> skinnedNode(scene.nodes.size(), false);
    for (const SkinnedNode& s : skinned)
        if (s.sceneNode < skinnedNode.size()) skinnedNode[s.sceneNode] = true;
    bool skinMoved = false;
    for (size_t i = 0; i < scene.nodes.size() && i < nodeSources.size(); ++i) {
        const auto& [gltfNode, below] = nodeSources[i];
        if (skinnedNode[i]) {
            skinMoved = skinMoved || movesUnder(gltfNode);
            continue;
        }
        if (!movesUnder(gltfNode)) continue;
        Node& node = scene.nodes[i];
        node.animation = anim;
        node.animationNode = int32_t(gltfNode);
        node.animationLocal = below;
        node.world = node.at(0.0);  // where the first frame has it
        node.dynamic = !still;
        if (still) node.animation.reset();
    }
    // Joints moved by it would pose the skin anew each frame; the skin keeps the load's pose.
    for (const SkinnedNode& s : skinned)
        for (int j :
             model.nodes[s.node].skin >= 0 && size_t(model.nodes[s.node].skin) < model.skins.size()
                 ? model.skins[size_t(model.nodes[s.node].skin)].joints
                 : std::vector<int>{})
            if (j >= 0 && size_t(j) < moved.size() && walkParent[size_t(j)] != -2 &&
                movesUnder(size_t(j)))
                skinMoved = true;
    if (skinMoved)
        warn(where +
             " moves a skinned mesh or its joints, which rgraph draws in the pose it loads "
             "with (skins are not animated)");
    // Lights and cameras stay where the file puts them at rest.
    for (size_t i = 0; i < model.nodes.size(); ++i) {
        const auto& n = model.nodes[i];
        const bool light = n.extensions.count("KHR_lights_punctual") > 0;
        if ((n.camera >= 0 || light) && walkParent[i] != -2 && movesUnder(i)) {
            warn(where + " moves " + named("node", i, n.name) + ", whose " +
                 (light ? "light" : "camera") +
                 " stays at its rest transform (rgraph animates meshes, not lights or cameras)");
            break;
        }
    }
    return {};
}

}  // namespace gltf_load

}  // namespace rg

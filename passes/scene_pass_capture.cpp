// The `scene` pass kind's probe capture (capture = true, CaptureScenePass): the scene's local light
// probes drawn into the six faces of their cubes, each face's draws front to back.
#include <algorithm>

#include <glm/glm.hpp>

#include "scene_pass_detail.h"

namespace rg::passes {

using namespace rg::gpu;
using namespace rg::passes::detail;

namespace {

// Whether a world box can show in cube face `face` seen from `eye` (the faces of
// shaders/lib/environment.glsl's rgCubeDirection: forward F, and the axes U, V along which the
// face's s and t grow): not when all eight corners lie outside one of the face's four side planes
// |r·U| <= r·F, |r·V| <= r·F. Conservative: a box that straddles is kept.
bool boxInCubeFace(const glm::vec3& lo, const glm::vec3& hi, const glm::vec3& eye, uint32_t face) {
    static const glm::vec3 kAxes[6][3] = {
        {{1, 0, 0}, {0, 0, -1}, {0, -1, 0}}, {{-1, 0, 0}, {0, 0, 1}, {0, -1, 0}},
        {{0, 1, 0}, {1, 0, 0}, {0, 0, 1}},   {{0, -1, 0}, {1, 0, 0}, {0, 0, -1}},
        {{0, 0, 1}, {1, 0, 0}, {0, -1, 0}},  {{0, 0, -1}, {-1, 0, 0}, {0, -1, 0}}};
    const glm::vec3 F = kAxes[face][0], U = kAxes[face][1], V = kAxes[face][2];
    const glm::vec3 planes[4] = {F - U, F + U, F - V, F + V};  // inside: dot(r, plane) >= 0
    for (const glm::vec3& n : planes) {
        bool allOutside = true;
        for (int c = 0; c < 8 && allOutside; ++c) {
            const glm::vec3 corner((c & 1) ? hi.x : lo.x, (c & 2) ? hi.y : lo.y,
                                   (c & 4) ? hi.z : lo.z);
            allOutside = glm::dot(corner - eye, n) < 0.0f;
        }
        if (allOutside) return false;
    }
    return true;
}

}  // namespace

// capture = true: the scene's local light probes (scripts/probes.lua), each into six layers
// of the colour target (cube k = probe k of GpuScene::probeOrder) with a depth target of as
// many layers: every draw that is not blended, through probes/capture.vert (the face's
// projection from the probe) and probes/capture.frag (diffuse only, metals with f0 as albedo,
// alpha 1 where something is drawn), one variant per set of textures.
Result<void> CaptureScenePass::prepareDraws(PassSetup& setup) {
    const PassDesc& desc = setup.desc;
    if (auto r = findAttachments(desc, /*depthRead=*/false, kWritesDepth); !r) return r;
    const std::vector<std::string> attachments = colorNames();
    sizeFromDepth(setup);
    if (m_colors.size() != 1)
        return fail(
            ErrorCode::InvalidInput,
            passPrefix(desc) +
                "a probe capture writes one colour target (a cube texture, 6 layers per probe)");
    const PlanResource& color = *setup.resources.find(m_colors.front().resource)->plan;
    const PlanResource& depth = *setup.resources.find(m_depth->resource)->plan;
    if (!color.cube)
        return fail(ErrorCode::InvalidInput, passPrefix(desc) +
                                                 "a probe capture writes a cube texture; '" +
                                                 color.name + "' is not one (cube = true)");
    if (depth.width != color.width || depth.height != color.height || depth.layers < color.layers)
        return fail(ErrorCode::InvalidInput, passPrefix(desc) + "the depth target '" + depth.name +
                                                 "' must match '" + color.name +
                                                 "' in size and have as many layers (" +
                                                 std::to_string(color.layers) + ")");
    m_layers = color.layers;
    const std::string vertex =
        desc.params["shader"].isString() ? desc.params["shader"].asString() : "probes/capture.vert";
    const std::string fragment = desc.params["fragment"].isString()
                                     ? desc.params["fragment"].asString()
                                     : "probes/capture.frag";
    // Each material with a surface function and a complete layout through a capture shader
    // generated from it (unless the pass names its own `fragment`); the rest, and a material
    // completed by a fix-up pass, through the fragment shader as the standard material.
    const bool generated = !desc.params["fragment"].isString();
    std::vector<PassMaterial> materials = generated ? desc.materials : std::vector<PassMaterial>{};
    std::erase_if(materials,
                  [](const PassMaterial& m) { return !m.fixup.empty() || m.surface.empty(); });
    auto own = [&](const Material& m) {
        return std::any_of(materials.begin(), materials.end(),
                           [&](auto& i) { return i.name == m.model; });
    };
    for (const PassMaterial& info : materials) {
        auto variants = drawsByTextures(*sceneOf(setup), [&](const Material& m) {
            return m.alphaMode != AlphaMode::Blend && m.model == info.name;
        });
        for (auto& [mask, draws] : variants) {
            ShaderRequest frag;
            frag.source = captureSource(info);
            frag.virtualName = "capture_" + info.name + ".frag";
            frag.stage = ShaderStage::Fragment;
            if (auto r = addGroup(setup, info, vertex, std::move(frag), mask, std::move(draws),
                                  attachments);
                !r)
                return r;
        }
    }
    auto variants = drawsByTextures(*sceneOf(setup), [&](const Material& m) {
        return m.alphaMode != AlphaMode::Blend && !own(m);
    });
    if (variants.empty() && m_groups.empty()) variants[31u];
    for (auto& [mask, draws] : variants) {
        PassMaterial info;
        info.name = "capture";
        ShaderRequest frag;
        frag.path = fragment;
        if (auto r =
                addGroup(setup, info, vertex, std::move(frag), mask, std::move(draws), attachments);
            !r)
            return r;
    }
    return {};
}

void CaptureScenePass::recordDraws(RecordContext& rc) {
    const PhysicalResource* c = rc.resources.find(m_colors.front().resource);
    const PhysicalResource* d = rc.resources.find(m_depth->resource);
    const uint32_t layers =
        std::min<uint32_t>(m_layers, 6u * static_cast<uint32_t>(sceneOf(rc)->probeOrder().size()));
    const auto& probes = sceneOf(rc)->scene().probes;
    const auto& order = sceneOf(rc)->probeOrder();
    std::vector<std::pair<size_t, size_t>> drawOrder;  // (group, draw)
    std::vector<float> distance(sceneOf(rc)->draws().size(), 0.0f);
    for (uint32_t layer = 0; layer < layers; ++layer) {
        // Cleared to (0, 0, 0, 0): where nothing is drawn, the distant probe shows.
        beginLayer(rc, c->image->layerView(layer), d->image->layerView(layer),
                   VK_ATTACHMENT_STORE_OP_DONT_CARE);
        // The face's draws front to back across every group (by the distance from the probe to
        // their boxes), switching pipelines as needed: a capture fragment casts a shadow ray
        // per light, so one the depth test rejects before it is shaded saves far more than a
        // pipeline bind (default scene: the capture ~213 -> ~190 ms).
        const glm::vec3 eye = probes[order[layer / 6]].position;
        drawOrder.clear();
        for (size_t gi = 0; gi < m_groups.size(); ++gi)
            for (size_t i : m_groups[gi].draws) {
                const DrawItem& item = sceneOf(rc)->draws()[i];
                // A moving node is left out: a probe captured once would keep it where it was.
                if (sceneOf(rc)->drawMoves(i)) continue;
                if (!boxInCubeFace(item.boundsMin, item.boundsMax, eye, layer % 6))
                    continue;  // beside this face
                distance[i] = glm::distance(glm::clamp(eye, item.boundsMin, item.boundsMax), eye);
                drawOrder.emplace_back(gi, i);
            }
        std::stable_sort(drawOrder.begin(), drawOrder.end(), [&](const auto& a, const auto& b) {
            return distance[a.second] < distance[b.second];
        });
        size_t bound = SIZE_MAX;
        for (const auto& [gi, i] : drawOrder) {
            Group& g = m_groups[gi];
            if (gi != bound) {
                vkCmdBindPipeline(rc.cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, g.pipeline.get());
                g.program->bind(rc, VK_PIPELINE_BIND_POINT_GRAPHICS);
                vkCmdSetStencilReference(rc.cmd, VK_STENCIL_FACE_FRONT_AND_BACK, 0);
                vkCmdSetCullMode(
                    rc.cmd, VK_CULL_MODE_NONE);  // the faces' projections do not keep one winding
                bound = gi;
            }
            const DrawItem& item = sceneOf(rc)->draws()[i];
            sceneOf(rc)->bindMaterial(rc.cmd, g.program->layout(), item.material);
            struct {
                glm::mat4 world;
                glm::vec4 layer;
            } push{item.world, glm::vec4(static_cast<float>(layer))};
            vkCmdPushConstants(rc.cmd, g.program->layout(),
                               VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                               sizeof push, &push);
            vkCmdDrawIndexed(rc.cmd, item.indexCount, 1, item.firstIndex, item.vertexOffset, 0);
        }
        vkCmdEndRendering(rc.cmd);
    }
}

}  // namespace rg::passes

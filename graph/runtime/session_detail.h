// What session.cpp shares with the files beside it (session_scene.cpp, session_captures.cpp);
// not part of the runtime's interface.
#pragma once

#include <string>
#include <vector>

#include "session.h"

namespace rg::detail {

// A value for parameter `name` of `pipeline`, checked against its type and range: what --set,
// the golden tests' params and `rgraph serve`'s controls all go through.
Result<Value> checkedParam(const PipelineDesc& pipeline, const std::string& name,
                           const Value& value);

bool hasScenePass(const PipelineDesc& p);

// What a debug view may ask of the scene (rg.view's v.scene): its lights and baked lightmap.
ViewFacts viewFactsOf(const Scene& scene);

// Sets the scene settings the pipeline's parameters drive (rg.param's `scene`); an error names the
// parameter where it was declared.
Result<void> applySceneSettings(passes::GpuScene& scene, const PipelineDesc& pipeline);

// `--capture` names (and the library's keep, serve's image requests) checked against a pipeline:
// a resource of its graph, or "gbuffer.<channel>" / "<layout>.<channel>", decoded per materialId.
Result<std::vector<Session::ChannelCapture>> channelCapturesOf(
    const PipelineDesc& pipeline, const std::vector<std::string>& captures);

}  // namespace rg::detail

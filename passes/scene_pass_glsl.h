// The GLSL rgraph generates for a pipeline material of the `scene` pass kind (scene_pass_glsl.cpp):
// its G-buffer, forward and probe capture fragment shaders, from the material's layout and
// surface function.
#pragma once

#include <string>
#include <vector>

#include "core/graph.h"  // PassMaterial

namespace rg::passes::detail {

// The shaders of one material; each generator says what its shader does. `specularTarget`: the
// attachment the scene pass's `lightmap_specular` names (scripts/render_loop.lua), which receives
// from every material the baked lightmap's pre-filtered specular radiance along the surface's
// reflection (lib/lightmap.glsl rgLightmapSpecular; black without a lightmap) for the reflection
// composition; "" or an attachment the pass does not have: none.
// `motionTarget` (both): the attachment the pass's `motion` names, which receives each pixel's
// screen motion since the last frame (lib/motion.glsl rgClipMotion, from scene.vert's RG_MOTION
// positions); the forward pass writes it with the surface's opacity as alpha, blended as the
// colour is.
std::string fragmentSource(const PassMaterial& m, const std::vector<std::string>& attachments,
                           const std::string& specularTarget, const std::string& motionTarget);
std::string forwardSource(const PassMaterial& m, const std::vector<std::string>& attachments,
                          const std::string& motionTarget);
std::string captureSource(const PassMaterial& m);

}  // namespace rg::passes::detail

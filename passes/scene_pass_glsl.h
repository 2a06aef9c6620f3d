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
std::string fragmentSource(const PassMaterial& m, const std::vector<std::string>& attachments,
                           const std::string& specularTarget);
std::string forwardSource(const PassMaterial& m);
std::string captureSource(const PassMaterial& m);

}  // namespace rg::passes::detail

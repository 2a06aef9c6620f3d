// The `scene` pass kind (scene_pass.cpp; its instance: scene_pass_detail.h).
#pragma once

#include "gpu/pass_kind.h"

namespace rg::passes {

gpu::PassKindInfo scenePassKind();

}  // namespace rg::passes

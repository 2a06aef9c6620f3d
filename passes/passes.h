// The built-in pass kinds. Each is generic; a pipeline script gives it shaders and bindings.
//   fullscreen  raster   one triangle over the colour attachments; optional stencil test, blend
//   compute     compute  a compute shader, dispatched over a resource's size or explicit groups
//   clear       transfer clears its copy destinations to params.value / params.depth / params.stencil
//   copy        transfer copies (same size and format) or blits (scaled) its CopySrc into its CopyDst
//   mips        transfer fills mips 1..n-1 of its target from mip 0 by repeated linear blits
//   readback    transfer copies its CopySrc to host memory every frame (a side effect)
#pragma once

#include "gpu/pass_kind.h"

namespace rg::passes {

void registerBuiltinPassKinds(gpu::PassRegistry& registry);

}  // namespace rg::passes

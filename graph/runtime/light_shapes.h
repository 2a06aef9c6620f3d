// Area lights' emissive shapes (seed 002 §4.8: "the engine generates an emissive shape for every
// light"): what the camera, SSR and the local probes see of a sphere, disk, rect or tube light.
#pragma once

#include <cstddef>

#include "core/result.h"
#include "core/value.h"
#include "scene/scene.h"

namespace rg {

// For every sphere, disk, rect and tube light with Light::visible, appends its shape — a sphere,
// a one-sided disk or rectangle facing along the light's direction, a capsule along a tube's axis —
// as a mesh, a standard material that emits exactly the luminance the lighting gives the light
// (lighting::convertLights: tbl:12 or eq:12, its colour and temperature) over a black surface with
// no specular (f0 0), and a node that casts no shadow and that no ray cast sees (Node::lightShape):
// the light's own shadow maps and rays must not find it, nor the reference count it twice.
// `standardParams` is the pipeline's standard material's parameters (the material's defaults).
// Returns how many shapes were added; errors are the light table's (they name the light).
Result<size_t> addLightShapes(Scene& scene, const Value& standardParams);

}  // namespace rg

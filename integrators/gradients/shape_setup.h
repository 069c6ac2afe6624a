#pragma once
// The set-up of derivatives with respect to shape parameters (docs/inverse.md, "Shape and
// camera"): a parameter's slots and how they move the geometry, and the scene features the
// geometric derivative covers.

#include <optional>
#include <string>
#include <vector>

#include "integrators/gradients/gradient_setup.h"

namespace nx {

/// When `name` (canonical, declared differentiable) is a shape's or the camera's parameter:
/// adds its slots to `tangents` and returns the parameter; nullopt for any other parameter.
/// Throws nx::Error naming it when the scene holds what the geometric derivative does not cover
/// yet (media, textures, a lens, an environment map, a moving emitter, anisotropic roughness;
/// for the camera, shapes other than spheres and planes).
std::optional<GradientParameter> shapeParameter(SceneTangents& tangents, const SceneDesc& desc,
                                                const std::string& name, const RenderScene& base);

/// What the geometric derivatives of `tangents`' shape and camera slots miss in `scene`, one
/// message per cause (point and spot lights' shadows seen after a bounce, outlines seen through
/// delta lobes, outlines of shapes that do not move seen from points that do); empty when no
/// slot moves the geometry or nothing is missed.
std::vector<std::string> shapeCoverageWarnings(const RenderScene& scene,
                                               const SceneTangents& tangents);

} // namespace nx

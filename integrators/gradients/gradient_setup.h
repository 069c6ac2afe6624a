#pragma once
// The set-up of a differentiated render by parameter names: each name's numbers
// (scene_params/parameter_numbers.h) become slots, and the scene's tangents for them are made
// by resolving copies of the description with each number moved a little (central
// differences; one-sided of second order at the end of a parameter's range). What
// render(gradients=...) in Python, the tests and nxbench-gradients use.

#include <cstdint>
#include <string>
#include <vector>

#include "integrators/gradients/scene_tangents.h"
#include "io/scene_desc.h"

namespace nx {

/// A differentiated parameter: its name and its slots.
struct GradientParameter {
  std::string name;
  uint32_t firstSlot = 0, slots = 1;
  bool indexed = false; ///< a vector: its gradient has a leading component axis
  /// The component axes' shape (a texture's (height, width, bands)); empty: (slots,)
  std::vector<long> shape;
};

/// The slots of a differentiated render and the scene's tangents for them.
struct GradientSetup {
  std::vector<GradientParameter> parameters;
  SceneTangents tangents;
  /// What the derivatives miss in this scene (a share of them, named with its cause), for the
  /// render to warn of; empty when they cover it all.
  std::vector<std::string> warnings;
};

/// The set-up for `names` (as sceneParameters names them) on `desc`, whose built scene is
/// `base`; `fluorescence` false: the copies are resolved without it (as the render is).
/// Throws nx::Error naming the parameter for an unknown name, one given twice, one not declared
/// differentiable (shape, camera, settings: docs/inverse.md) and one whose numbers cannot be
/// moved or written back as they are.
GradientSetup gradientSetup(const SceneDesc& desc, const std::vector<std::string>& names,
                            const RenderScene& base, bool fluorescence);

} // namespace nx

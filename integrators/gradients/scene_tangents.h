#pragma once
// The derivatives of a scene's appearance data with respect to the parameters being
// differentiated (docs/inverse.md): per parameter component ("slot"), what changes in which
// material, emitter or light, as tables the path tracer reads next to the scene's own. Made by
// differencing scenes resolved at nearby parameter values (the resolution is deterministic and
// smooth in every differentiable parameter), so every parameter of every kind is covered by
// the same code; the render's derivative itself is estimated along the paths (path_gradients.h).

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "integrators/render_scene.h"

namespace nx {

/// d spectrum / d parameter for one slot, sampled every 0.25 nm over the traced range.
struct SpectrumTangent {
  uint32_t slot = 0;
  Spectrum d;
};

/// d M / d parameter of a re-radiation matrix for one slot: the cells, and the elastic part
/// D(o) = scale(o) rho + constant(o) (ReradiationMatrix::elastic).
struct MatrixTangent {
  uint32_t slot = 0;
  std::vector<float> cells; ///< [i * kBins + o], as the matrix's cells
  std::array<float, ReradiationMatrix::kBins> elasticScale{}, elasticConstant{};
};

/// d / d parameter of a homogeneous medium for one slot: its coefficients, its phase function's
/// g, and its dye (peak and matrix: absorptance a, column sums c, cells M per peak 1).
struct MediumTangent {
  uint32_t slot = 0;
  Spectrum sigmaA, sigmaS; ///< d sigma_a, d sigma_s
  float g = 0, dyePeak = 0;
  std::vector<float> dyeCells; ///< [i * kBins + o]; empty without a dye
  std::array<float, ReradiationMatrix::kBins> dyeAbsorptance{}, dyeColumnSum{};
};

/// Every slot's derivatives, indexed like the scene's tables.
struct SceneTangents {
  std::vector<std::string> slotNames; ///< what each slot is, e.g. "objects[1].reflectance[3]"
  std::vector<std::vector<SpectrumTangent>> reflectance; ///< per RenderScene::materials
  std::vector<std::vector<MatrixTangent>> reradiation;   ///< per RenderScene::materials
  std::vector<std::vector<SpectrumTangent>> emission;    ///< per RenderScene::emission
  std::vector<std::vector<SpectrumTangent>> lights;      ///< per RenderScene::lights (intensity)
  std::vector<SpectrumTangent> background;
  std::vector<std::vector<MediumTangent>> media; ///< per RenderScene::media
  /// Slots whose parameter changes nothing the scene renders (their derivative is 0).
  std::vector<uint32_t> inert;

  /// Number of slots.
  uint32_t slots() const { return static_cast<uint32_t>(slotNames.size()); }
  /// Tables sized for `scene`, no slot yet.
  static SceneTangents sizedFor(const RenderScene& scene);
};

/// Adds slot `name`: the derivative of `base`'s appearance data as sum_i weights[i] * scenes[i]
/// (a finite-difference stencil over scenes resolved at nearby values of one parameter, e.g.
/// (+1/2h, -1/2h)). Throws nx::Error naming `name` when the scenes differ in what is not
/// differentiated (structure, geometry, roughness, indices of refraction, textures, environment
/// maps, a medium's emission or an emitting medium's absorption) or when fluorescence appears or
/// vanishes. Returns the new slot.
uint32_t addTangentSlot(SceneTangents& tangents, const std::string& name, const RenderScene& base,
                        std::span<const RenderScene* const> scenes,
                        std::span<const double> weights);

} // namespace nx

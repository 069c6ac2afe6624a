#pragma once
// The rough diffuse model's constants and closed forms (rough_diffuse.cpp), for its tests.

#include <array>

#include "integrators/materials/material.h"

namespace nx {

/// The rough diffuse lobe's constants for one roughness sigma: Fujii's A and B, and the
/// single-scattering lobe's directional albedo E(mu) tabulated over mu = cos (uniform nodes,
/// interpolated by Catmull-Rom) with its cosine-weighted mean. Stored as the material's
/// `modelConstants`.
struct RoughDiffuseLobe {
  static constexpr int kNodes = 33;
  float a = 1, b = 0;
  std::array<float, kNodes> albedo{};
  float meanAlbedo = 1;
};

/// The lobe constants of a rough diffuse material (MaterialKind::RoughDiffuse).
const RoughDiffuseLobe& roughDiffuseLobeOf(const Material& m);

/// The single-scattering lobe's directional albedo E(mu) at rho = 1.
float roughDiffuseAlbedo(const RoughDiffuseLobe& lobe, float mu);

/// EON's multiple-scattering albedo rho_ms = rho^2 E_avg / (1 - rho (1 - E_avg)).
float roughDiffuseMultipleAlbedo(const RoughDiffuseLobe& lobe, float rho);

} // namespace nx

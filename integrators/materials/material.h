#pragma once
// A material as the integrators see it: a kind from a fixed set and its resolved parameters
// (spectra, indices, matrices), no names. Made from a scene's parameters by its kind's build
// (integrators/materials/material_kind.h).

#include <array>
#include <cstdint>
#include <memory>
#include <optional>

#include "core/params/concentration_map.h"
#include "integrators/ior_model.h"
#include "spectra/reflectance_texture.h"
#include "spectra/reradiation_matrix.h"
#include "spectra/spectrum.h"

namespace nx {

/// How a surface scatters light.
enum class MaterialKind : uint8_t {
  Mixture,        ///< (1 - r) rho * ideal mirror + r rho / pi (matte r = 1, mirror r = 0)
  Dielectric,     ///< smooth dielectric: exact Fresnel, refraction, total internal reflection
  Interface,      ///< the boundary of a medium with the same index on both sides: light passes
                  ///< unchanged (no reflection, no refraction)
  ThinDielectric, ///< a thin glass wall (parallel faces): Fresnel reflection with the
                  ///< internal reflections summed, and straight transmission
  Conductor,      ///< a metal: GGX microfacets (smooth when alpha is 0) with the exact Fresnel
                  ///< reflectance of its complex index
  CoatedDiffuse,  ///< a Lambertian base (possibly fluorescent) under a smooth clear coat, the
                  ///< internal reflections between them summed
  RoughDiffuse,   ///< a rough diffuse surface (possibly fluorescent): Fujii's Oren-Nayar lobe
                  ///< with the energy its single scattering loses put back (EON)
};

/// The rough diffuse lobe's constants for one roughness sigma (kinds/rough_diffuse.cpp): Fujii's
/// A and B, and the single-scattering lobe's directional albedo E(mu) tabulated over mu = cos
/// (uniform nodes, interpolated by Catmull-Rom) with its cosine-weighted mean.
struct RoughDiffuseLobe {
  static constexpr int kNodes = 33;
  float a = 1, b = 0;
  std::array<float, kNodes> albedo{};
  float meanAlbedo = 1;
};

/// A material: a kind with its parameters and spectra.
struct Material {
  MaterialKind kind = MaterialKind::Mixture;
  float roughness = 1;               ///< Mixture: probability weight r of the diffuse lobe
  IorModel ior;                      ///< Dielectric
  Spectrum conductorEta, conductorK; ///< Conductor: complex index eta + i k
  float alphaU = 0, alphaV = 0;      ///< Conductor: GGX roughness along dpdu and across it
  /// CoatedDiffuse: the coat's hemispherical (cosine-weighted) internal Fresnel reflectance
  float coatInternalReflectance = 0;
  RoughDiffuseLobe roughDiffuse; ///< RoughDiffuse: its lobe's constants
  float coatingNm = 0;           ///< a thin-film coating's thickness in nm (0: none)
  IorModel coatingIor;           ///< the coating's index of refraction
  Spectrum reflectance;          ///< rho(lambda): albedo, or transmission tint for dielectrics
  std::optional<FluorescenceModel> fluorescenceModel; ///< the parameters, if not measured
  std::shared_ptr<const ReradiationMatrix>
      reradiation; ///< fluorescence of the diffuse lobe, or null
  /// The dye's relative concentration over the surface (by the hit's uv), scaling the matrix's
  /// absorptance there (ReradiationMatrix::sampleExcitationScaled); or null: 1 everywhere
  std::shared_ptr<const ConcentrationMap> concentration;
  /// A reflectance varying over the surface (by the hit's uv), replacing `reflectance`; or null
  std::shared_ptr<const ReflectanceTexture> texture;
};

} // namespace nx

#pragma once
// A material as the integrators see it: a kind from a fixed set and its resolved parameters
// (spectra, indices, matrices), no names. Made from a scene's parameters by its kind's build
// (integrators/materials/material_kind.h).

#include <cstdint>
#include <memory>
#include <optional>

#include "core/params/concentration_map.h"
#include "integrators/ior_model.h"
#include "spectra/reflectance_texture.h"
#include "spectra/reradiation_matrix.h"
#include "spectra/spectrum.h"

namespace nx {

/// The scattering models, one file each in integrators/materials/kinds/ (its lobes, sampling,
/// densities and derivatives as `ScatteringModel<MaterialKind::X>`, scattering_model.h). This
/// list is their registry: the enum below, SurfaceBsdf's dispatch and the conformance tests'
/// cases are generated from it, so a model missing a method does not link.
#define NX_SCATTERING_MODELS(X)                                                                    \
  X(Mixture)        /* (1 - r) rho mirror + r rho / pi: matte r = 1, mirror r = 0 (mixture.cpp) */ \
  X(Dielectric)     /* exact Fresnel, refraction, TIR; smooth or GGX-rough (dielectric.cpp) */     \
  X(Interface)      /* an index-matched medium boundary: light passes unchanged (interface.cpp) */ \
  X(ThinDielectric) /* a thin glass wall: internal reflections summed, straight through */         \
  X(Conductor)      /* a metal: GGX microfacets, exact Fresnel of eta + i k (conductor.cpp) */     \
  X(CoatedDiffuse)  /* a Lambertian base under a smooth clear coat (coated_diffuse.cpp) */         \
  X(RoughDiffuse)   /* Fujii's Oren-Nayar with EON's multiple scattering (rough_diffuse.cpp) */

/// How a surface scatters light: one value per scattering model (NX_SCATTERING_MODELS).
enum class MaterialKind : uint8_t {
#define NX_MODEL_ENUMERATOR(name) name,
  NX_SCATTERING_MODELS(NX_MODEL_ENUMERATOR)
#undef NX_MODEL_ENUMERATOR
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
  /// Constants a scattering model derives when the material is built (a table, a fit), of a
  /// type only its own file knows (`modelConstantsAs`); or null. A model shares them between
  /// materials of equal parameters, so the pointers differ exactly when the parameters do.
  std::shared_ptr<const void> modelConstants;
  float coatingNm = 0;  ///< a thin-film coating's thickness in nm (0: none)
  IorModel coatingIor;  ///< the coating's index of refraction
  Spectrum reflectance; ///< rho(lambda): albedo, or transmission tint for dielectrics
  std::optional<FluorescenceModel> fluorescenceModel; ///< the parameters, if not measured
  std::shared_ptr<const ReradiationMatrix>
      reradiation; ///< fluorescence of the diffuse lobe, or null
  /// The dye's relative concentration over the surface (by the hit's uv), scaling the matrix's
  /// absorptance there (ReradiationMatrix::sampleExcitationScaled); or null: 1 everywhere
  std::shared_ptr<const ConcentrationMap> concentration;
  /// A reflectance varying over the surface (by the hit's uv), replacing `reflectance`; or null
  std::shared_ptr<const ReflectanceTexture> texture;

  /// The model's constants as the type its file stored (it alone knows that type).
  template <class T>
  const T& modelConstantsAs() const {
    return *static_cast<const T*>(modelConstants.get());
  }
};

} // namespace nx

#pragma once
// What a scattering model provides, and the state it works on. Each model of
// NX_SCATTERING_MODELS (material.h) defines every member of `ScatteringModel<MaterialKind::X>`
// in its own file of integrators/materials/kinds/; SurfaceBsdf (bsdf.h) dispatches to them by a
// switch generated from the list. The members are declared below for every listed model, so a
// model that leaves one out fails to link, and a listed kind without a case fails to compile.

#include <algorithm>
#include <cstdint>
#include <cstdlib>

#include "core/frame.h"
#include "core/sampler.h"
#include "integrators/materials/material.h"
#include "integrators/materials/microfacet.h"
#include "spectra/sampled_wavelengths.h"

namespace nx {

/// A sampled scattering direction and its Monte Carlo weight per wavelength.
struct BsdfSample {
  Vec3 wi;                         ///< new direction (world space, unit)
  SampledSpectrum weight;          ///< f * |cos(wi)| / pdf, per lane
  float pdf = 0;                   ///< density of wi if drawn from the continuous part, else 0
  bool specular = false;           ///< drawn from a delta lobe (mirror, refraction)
  bool terminateSecondary = false; ///< the direction depends on the hero wavelength (dispersion)
  /// Relative index n_transmitted / n_incident of the hero lane for a refraction, else 1: the
  /// radiance scaling 1 / eta^2 inside `weight` that Russian roulette must not see.
  float eta = 1;
  /// For a diffuse-lobe sample: the weight per unit albedo (1 for a plain Lambertian lobe; the
  /// coat's transmission and internal reflections for CoatedDiffuse), so a fluorescent lobe's
  /// weight is its re-radiation albedo times this.
  SampledSpectrum diffuseScale = SampledSpectrum::filled(1.0f);
  /// The direction continues straight on (an interface, a thin wall's transmission): the path
  /// keeps its previous vertex for MIS, since next-event estimation sees through such surfaces.
  bool straight = false;
};

/// A delta lobe of a surface: its one direction and the fraction of radiance it carries per
/// lane (for a refraction including the 1/eta^2 radiance scaling).
struct SpecularLobe {
  Vec3 wi;
  SampledSpectrum weight;
  bool heroOnly = false; ///< the direction is the hero wavelength's (a dispersive refraction)
};

/// The kinds of scattering a BSDF has (bit flags): integrators ask for what they need (can a
/// light be sampled here? is there a delta lobe?) without naming a material's lobes.
enum BsdfLobe : uint8_t {
  kDiffuseReflection = 1,
  kGlossyReflection = 2,
  kSpecularReflection = 4,
  kDiffuseTransmission = 8,
  kGlossyTransmission = 16,
  kSpecularTransmission = 32,
  /// With kSpecularTransmission: the delta transmission goes straight on, without refraction
  /// (an interface, a thin wall), so shadow rays pass through (`straightTransmittance`).
  kStraightTransmission = 64,
  kNonSpecular =
      kDiffuseReflection | kGlossyReflection | kDiffuseTransmission | kGlossyTransmission,
};

/// Whether weights carry the 1/eta^2 radiance scaling at refraction (camera paths) or not
/// (energy, used to check conservation).
enum class TransportMode : uint8_t { Radiance, Energy };

/// Steps, in radians of its unit-vector arguments, for differences of a BSDF
/// (geometry_gradients.h): one for turning its normals, one for turning wo and wi.
struct BsdfDerivativeSteps {
  float normals = 1e-3f, directions = 1e-3f;
};

/// One surface point's scattering state, shared by the models: set by SurfaceBsdf's
/// constructor (material, wavelengths, rho, normals, wo, mode), then by the model's `prepare`
/// (which side is up, its own per-lane constants).
struct BsdfState {
  const Material* material = nullptr;
  const SampledWavelengths* lambda = nullptr;
  SampledSpectrum rho; ///< the material's reflectance at the path's wavelengths
  /// Shading and geometric normals: as given, until an opaque model turns both to wo's side.
  Vec3 n, ng;
  Vec3 wo; ///< towards the previous vertex (unit)
  TransportMode mode = TransportMode::Radiance;
  /// Per-lane constants of microfacet models: a conductor's complex index eta + i k; a rough
  /// dielectric's relative index n_other / n_wo-side in eta.
  SampledSpectrum eta, k;
  GgxDistribution alpha;  ///< microfacet roughness (0, 0: none or smooth)
  Frame frame;            ///< the microfacet frame (n as z)
  bool heroAlone = false; ///< the path carries the hero lane alone (after dispersion)
  uint8_t lobes = 0;      ///< the model's BsdfLobe flags for this material

  /// Turns both normals to wo's geometric side: an opaque surface scatters on the side it is
  /// seen from.
  void faceWo() {
    if (dot(wo, ng) < 0) ng = -ng, n = -n;
  }
};

/// A scattering model's methods; only explicit specializations exist (one file per model).
template <MaterialKind K>
struct ScatteringModel {
  /// The lobes a material of this model has (BsdfLobe flags), from the material alone.
  static uint8_t lobes(const Material& m);
  /// Completes the state after the common fields: the side (faceWo for opaque models) and
  /// per-lane constants.
  static void prepare(BsdfState& s);
  /// f(wo, wi) |cos(wi)| of the non-specular lobes, per lane (zero below the surface).
  static SampledSpectrum f(const BsdfState& s, const Vec3& wi);
  /// The diffuse lobe per unit albedo, per lane (what a fluorescent lobe scales by its
  /// re-radiation albedo); zero for a model without a diffuse lobe.
  static SampledSpectrum diffuseLobe(const BsdfState& s, const Vec3& wi);
  /// Density with which `sample` returns wi through its non-specular lobes.
  static float pdf(const BsdfState& s, const Vec3& wi);
  /// Draws a direction (uLobe picks the lobe, u the direction in it); false: nothing scattered.
  static bool sample(const BsdfState& s, float uLobe, Sample2 u, BsdfSample& out);
  /// Every delta lobe with its full weight, reflection first; how many (0-2).
  static int specularLobes(const BsdfState& s, SpecularLobe (&out)[2]);
  /// d ln f / d rho of the lobe towards wi at one lane of reflectance rho (SurfaceBsdf's
  /// reflectanceLogSlope documents the arguments).
  static float reflectanceLogSlope(const BsdfState& s, const Vec3& wi, float rho, bool specular,
                                   bool albedo, bool& zero);
  /// d ln f / d alpha_u and / d alpha_v where the model differentiates its roughness; false
  /// where it does not.
  static bool roughnessLogSlopes(const BsdfState& s, const Vec3& wi, float& dAlphaU,
                                 float& dAlphaV);
  /// Steps for differences of the model's lobes (geometry_gradients.h): small against the
  /// narrowest lobe it has.
  static BsdfDerivativeSteps derivativeSteps(const Material& m);
  /// The fraction per lane that a straight transmission (kStraightTransmission) lets through
  /// at cosine `cosine` to the normal, for shadow rays; 0 where the model has none.
  static SampledSpectrum straightTransmittance(const Material& m, const SampledWavelengths& lambda,
                                               float cosine);
  /// True where the directional albedo is the reflectance rho from every direction (the
  /// ground-truth albedo layer then reads rho instead of integrating the lobes).
  static bool albedoIsReflectance(const Material& m);
  /// True where gradients may move the microfacet roughness alpha_u, alpha_v (the model's
  /// `roughnessLogSlopes` give its derivative); false where a change of it is refused.
  static bool roughnessDifferentiable(const Material& m);
};

// Every listed model's members, declared as explicit specializations (defined in its file).
#define NX_DECLARE_SCATTERING_MODEL(name)                                                          \
  template <>                                                                                      \
  uint8_t ScatteringModel<MaterialKind::name>::lobes(const Material&);                             \
  template <>                                                                                      \
  void ScatteringModel<MaterialKind::name>::prepare(BsdfState&);                                   \
  template <>                                                                                      \
  SampledSpectrum ScatteringModel<MaterialKind::name>::f(const BsdfState&, const Vec3&);           \
  template <>                                                                                      \
  SampledSpectrum ScatteringModel<MaterialKind::name>::diffuseLobe(const BsdfState&, const Vec3&); \
  template <>                                                                                      \
  float ScatteringModel<MaterialKind::name>::pdf(const BsdfState&, const Vec3&);                   \
  template <>                                                                                      \
  bool ScatteringModel<MaterialKind::name>::sample(const BsdfState&, float, Sample2, BsdfSample&); \
  template <>                                                                                      \
  int ScatteringModel<MaterialKind::name>::specularLobes(const BsdfState&, SpecularLobe(&)[2]);    \
  template <>                                                                                      \
  float ScatteringModel<MaterialKind::name>::reflectanceLogSlope(const BsdfState&, const Vec3&,    \
                                                                 float, bool, bool, bool&);        \
  template <>                                                                                      \
  bool ScatteringModel<MaterialKind::name>::roughnessLogSlopes(const BsdfState&, const Vec3&,      \
                                                               float&, float&);                    \
  template <>                                                                                      \
  BsdfDerivativeSteps ScatteringModel<MaterialKind::name>::derivativeSteps(const Material&);       \
  template <>                                                                                      \
  SampledSpectrum ScatteringModel<MaterialKind::name>::straightTransmittance(                      \
      const Material&, const SampledWavelengths&, float);                                          \
  template <>                                                                                      \
  bool ScatteringModel<MaterialKind::name>::albedoIsReflectance(const Material&);
NX_SCATTERING_MODELS(NX_DECLARE_SCATTERING_MODEL)
#undef NX_DECLARE_SCATTERING_MODEL

/// Calls visit(ScatteringModel<kind>{}) for the model of `kind` (a switch generated from
/// NX_SCATTERING_MODELS: every kind has its case, and none has a default).
template <class Visit>
decltype(auto) visitScatteringModel(MaterialKind kind, Visit&& visit) {
  switch (kind) {
#define NX_SCATTERING_MODEL_CASE(name)                                                             \
  case MaterialKind::name:                                                                         \
    return visit(ScatteringModel<MaterialKind::name>{});
    NX_SCATTERING_MODELS(NX_SCATTERING_MODEL_CASE)
#undef NX_SCATTERING_MODEL_CASE
  }
  std::abort(); // not reached: a MaterialKind is one of the listed models
}

/// True when a surface's only lobe is a straight transmission (an index-matched boundary):
/// light crosses it unchanged, as if it were not there.
constexpr bool passesUnchanged(uint8_t lobes) {
  return lobes == (kSpecularTransmission | kStraightTransmission);
}

// ---- what several models share (bsdf.cpp) ----

/// d ln f / d rho = 1 / rho for a lobe linear in rho (`albedo` false: 0, the lobe's albedo is
/// a matrix's; rho = 0: `zero` set, 0 returned).
float inverseReflectanceSlope(float rho, bool albedo, bool& zero);

/// The steps of a microfacet lobe of roughness alphaU, alphaV: 1e-3, or an eighth of its
/// narrowest roughness where that is smaller (the defaults where it is smooth).
BsdfDerivativeSteps microfacetDerivativeSteps(const Material& m);

/// True where a material's microfacet roughness makes it rough (max alpha >= 1e-4); below that
/// its lobes are the smooth surface's deltas.
inline bool roughMicrofacets(const Material& m) {
  return std::max(m.alphaU, m.alphaV) >= 1e-4f;
}

/// GGX roughness as SurfaceBsdf uses it: each alpha at least 1e-4 where the surface is rough
/// (max alpha >= 1e-4), else 0, 0 (smooth).
GgxDistribution clampedGgx(const Material& m);

} // namespace nx

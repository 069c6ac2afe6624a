#pragma once
// Scattering at a surface point for all wavelengths of a path at once, dispatched statically
// over the fixed set of material kinds (no virtual call, nothing per wavelength but arithmetic).

#include <algorithm>

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
  kNonSpecular =
      kDiffuseReflection | kGlossyReflection | kDiffuseTransmission | kGlossyTransmission,
};

/// Whether weights carry the 1/eta^2 radiance scaling at refraction (camera paths) or not
/// (energy, used to check conservation).
enum class TransportMode : uint8_t { Radiance, Energy };

/// Reflectance of a smooth dielectric interface for light arriving with cosine cosI from the
/// side of index nIncident towards nTransmitted (absolute indices), through the material's
/// thin-film coating if it has one (on the outside of the surface), at wavelength lambdaNm.
float dielectricReflectance(const Material& m, float cosI, float nIncident, float nTransmitted,
                            float lambdaNm);

/// A rough diffuse lobe's factors at one pair of directions (kinds/rough_diffuse.cpp): the
/// single-scattering term A + B s / t, the multiple-scattering term (1 - E_o)(1 - E_i) /
/// (1 - E_avg) and cos_i (all 0 below the surface).
struct RoughDiffuseShape {
  float single = 0, multiple = 0, cosine = 0;
};

/// The rough diffuse single-scattering lobe's directional albedo E(mu) at rho = 1.
float roughDiffuseAlbedo(const RoughDiffuseLobe& lobe, float mu);

/// EON's multiple-scattering albedo rho_ms = rho^2 E_avg / (1 - rho (1 - E_avg)).
float roughDiffuseMultipleAlbedo(const RoughDiffuseLobe& lobe, float rho);

/// Steps, in radians of its unit-vector arguments, for differences of a BSDF
/// (geometry_gradients.h): one for turning its normals, one for turning wo and wi.
struct BsdfDerivativeSteps {
  float normals = 1e-3f, directions = 1e-3f;
};

/// m's steps: 1e-3, or an eighth of its narrowest microfacet roughness where that is smaller,
/// so that a difference spans a small part of the lobe at every roughness; a rough
/// dielectric's directions narrower still where its index is near 1 (its transmitted lobe).
BsdfDerivativeSteps bsdfDerivativeSteps(const Material& m);

/// The BSDF of one surface point, seen from direction wo.
class SurfaceBsdf {
public:
  /// Keeps references to `m` and `lambda` (they must outlive it).
  /// `rho` is the material's reflectance at the path's wavelengths; ng the geometric normal
  /// (outward for spheres), ns the shading normal (on ng's side; ng itself where the surface
  /// has none); wo points away from the surface (towards the previous vertex). Lobes are
  /// evaluated and sampled in ns's frame; a direction on the other geometric side of the
  /// surface than wo is never reflected (no light leaks through interpolated normals).
  SurfaceBsdf(const Material& m, const SampledWavelengths& lambda, const SampledSpectrum& rho,
              const Vec3& ng, const Vec3& ns, const Vec3& wo,
              TransportMode mode = TransportMode::Radiance);
  /// The same with the shading normal equal to the geometric one.
  SurfaceBsdf(const Material& m, const SampledWavelengths& lambda, const SampledSpectrum& rho,
              const Vec3& ng, const Vec3& wo, TransportMode mode = TransportMode::Radiance)
      : SurfaceBsdf(m, lambda, rho, ng, ng, wo, mode) {}

  /// The lobes this surface has (BsdfLobe flags).
  uint8_t lobes() const;
  /// True if some of the scattering is non-specular (light sampling can help).
  bool hasNonSpecular() const { return (lobes() & kNonSpecular) != 0; }

  /// Tells the BSDF that the path carries the hero lane alone (after dispersion): a dispersive
  /// rough dielectric's transmission in f() is then not scaled by kLanes again.
  void setHeroAlone(bool heroAlone) { heroAlone_ = heroAlone; }

  /// Orients anisotropic roughness: alpha_u runs along the surface tangent dpdu (projected
  /// onto the tangent plane; a degenerate tangent keeps an arbitrary orientation).
  void orient(const Vec3& dpdu);

  /// f(wo, wi) |cos(wi)| of the non-specular lobes, per lane (zero below the surface).
  SampledSpectrum f(const Vec3& wi) const {
    if (material_->kind == MaterialKind::Conductor) return conductorF(wi);
    if (material_->kind == MaterialKind::Dielectric) return roughDielectricF(wi);
    if (material_->kind == MaterialKind::CoatedDiffuse) return rho_ * diffuseLobe(wi);
    if (material_->kind == MaterialKind::RoughDiffuse) return roughDiffuseF(wi);
    return rho_ * diffuseFactor(wi);
  }
  /// r |cos(wi)| / pi: the diffuse lobe without its albedo (fluorescent lobes supply their own).
  float diffuseFactor(const Vec3& wi) const;
  /// The diffuse lobe per unit albedo, per lane: diffuseFactor for the mixture; for a coated
  /// diffuse surface with the coat's transmissions and internal reflections.
  SampledSpectrum diffuseLobe(const Vec3& wi) const;
  /// For a rough conductor: d ln f(wo, wi) / d alpha_u and / d alpha_v (its microfacet lobe's
  /// dependence on its roughness, for gradients); false for other surfaces and smooth metals.
  bool conductorRoughnessSlopes(const Vec3& wi, float& dAlphaU, float& dAlphaV) const;
  /// d ln f / d rho of the lobe that scattered towards wi (`specular`: a delta lobe) at one
  /// lane of reflectance rho, for reflectance gradients; 0 where f does not depend on rho (or
  /// `albedo` is false: a fluorescent lobe's albedo is the matrix's). `zero`: f is 0 with
  /// rho (its slope 1/rho is unbounded).
  float reflectanceLogSlope(const Vec3& wi, float rho, bool specular, bool albedo,
                            bool& zero) const;
  /// Density with which sample() returns wi through its non-specular lobes.
  float pdf(const Vec3& wi) const;

  /// Draws a direction: uLobe picks the lobe, u the direction within it. Returns false when
  /// nothing is scattered (a black surface).
  bool sample(float uLobe, Sample2 u, BsdfSample& out) const;

  /// Every delta lobe at once, each with its full weight (what Whitted ray tracing follows,
  /// instead of choosing one): reflection first, then transmission. Returns how many (0-2);
  /// glossy and diffuse lobes have none.
  int specularLobes(SpecularLobe (&out)[2]) const;

  /// The shading normal on the side of wo (Mixture) or the outward one (Dielectric).
  const Vec3& normal() const { return n_; }

private:
  bool sampleMixture(float uLobe, Sample2 u, BsdfSample& out) const;
  bool sampleConductor(Sample2 u, BsdfSample& out) const;
  bool sampleCoatedDiffuse(float uLobe, Sample2 u, BsdfSample& out) const;
  float coatReflectance(float cosI) const; // the clear coat's Fresnel reflectance from outside
  SampledSpectrum conductorF(const Vec3& wi) const;
  SampledSpectrum conductorFresnel(float cosI) const;
  bool smoothConductor() const { return !(std::max(alpha_.ax, alpha_.ay) > 0); }
  // Rough dielectrics (bsdf_rough_dielectric.cpp): wo's side as +z, the lanes' Fresnel.
  bool roughDielectric() const {
    return material_->kind == MaterialKind::Dielectric && std::max(alpha_.ax, alpha_.ay) > 0;
  }
  bool sampleRoughDielectric(float uLobe, Sample2 u, BsdfSample& out) const;
  bool roughDielectricPair(const Vec3& wi, Vec3& o, Vec3& i) const;
  SampledSpectrum roughDielectricF(const Vec3& wi) const;
  float roughDielectricPdf(const Vec3& wi) const;
  bool sampleDielectric(float uLobe, BsdfSample& out) const;
  bool sampleThinDielectric(float uLobe, BsdfSample& out) const;
  // Rough diffuse surfaces (kinds/rough_diffuse.cpp).
  RoughDiffuseShape roughDiffuseShape(const Vec3& wi) const;
  SampledSpectrum roughDiffuseF(const Vec3& wi) const;
  float roughDiffuseLogSlope(const Vec3& wi, float rho) const;
  bool sampleRoughDiffuse(Sample2 u, BsdfSample& out) const;

  const Material* material_;
  const SampledWavelengths* lambda_;
  SampledSpectrum rho_;
  Vec3 n_, ng_, wo_; ///< shading normal, geometric normal (both on wo's side for Mixture)
  TransportMode mode_;
  // Conductors: the lanes' complex index; rough dielectrics: eta_ the lanes' relative index
  // n_other / n_wo-side; both: the roughness and the microfacet frame (n_ as z).
  SampledSpectrum eta_, k_;
  GgxDistribution alpha_;
  Frame frame_;
  bool heroAlone_ = false;
};

} // namespace nx

#pragma once
// Scattering at a surface point for all wavelengths of a path at once, dispatched statically
// to the material's scattering model (scattering_model.h; no virtual call, nothing per
// wavelength but arithmetic).

#include "integrators/materials/scattering_model.h"

namespace nx {

/// m's steps for differences of its BSDF: its model's (1e-3, or an eighth of its narrowest
/// microfacet roughness where that is smaller, so that a difference spans a small part of the
/// lobe at every roughness; a rough dielectric's directions narrower still where its index is
/// near 1, its transmitted lobe).
BsdfDerivativeSteps bsdfDerivativeSteps(const Material& m);

/// The lobes a material has (BsdfLobe flags), from its model.
uint8_t materialLobes(const Material& m);

/// What a material's straight transmission lets through per lane at `cosine` (shadow rays
/// through interfaces and thin walls); 0 without one.
SampledSpectrum straightTransmittance(const Material& m, const SampledWavelengths& lambda,
                                      float cosine);

/// True where a material's directional albedo is its reflectance from every direction.
bool albedoIsReflectance(const Material& m);

/// True where gradients may move a material's microfacet roughness (its model's choice).
bool roughnessDifferentiable(const Material& m);

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
  uint8_t lobes() const { return s_.lobes; }
  /// True if some of the scattering is non-specular (light sampling can help).
  bool hasNonSpecular() const { return (lobes() & kNonSpecular) != 0; }

  /// Tells the BSDF that the path carries the hero lane alone (after dispersion): a dispersive
  /// rough dielectric's transmission in f() is then not scaled by kLanes again.
  void setHeroAlone(bool heroAlone) { s_.heroAlone = heroAlone; }

  /// Orients anisotropic roughness: alpha_u runs along the surface tangent dpdu (projected
  /// onto the tangent plane; a degenerate tangent keeps an arbitrary orientation).
  void orient(const Vec3& dpdu);

  /// f(wo, wi) |cos(wi)| of the non-specular lobes, per lane (zero below the surface).
  SampledSpectrum f(const Vec3& wi) const {
    return visitScatteringModel(s_.material->kind,
                                [&](auto model) { return decltype(model)::f(s_, wi); });
  }
  /// The diffuse lobe per unit albedo, per lane: r |cos(wi)| / pi for the mixture; for a coated
  /// diffuse surface with the coat's transmissions and internal reflections; zero where there
  /// is none (fluorescent lobes supply their own albedo).
  SampledSpectrum diffuseLobe(const Vec3& wi) const {
    return visitScatteringModel(s_.material->kind,
                                [&](auto model) { return decltype(model)::diffuseLobe(s_, wi); });
  }
  /// d ln f(wo, wi) / d alpha_u and / d alpha_v where the model differentiates its roughness
  /// (a rough conductor's microfacet lobe); false for other surfaces and smooth metals.
  bool roughnessLogSlopes(const Vec3& wi, float& dAlphaU, float& dAlphaV) const {
    return visitScatteringModel(s_.material->kind, [&](auto model) {
      return decltype(model)::roughnessLogSlopes(s_, wi, dAlphaU, dAlphaV);
    });
  }
  /// d ln f / d rho of the lobe that scattered towards wi (`specular`: a delta lobe) at one
  /// lane of reflectance rho, for reflectance gradients; 0 where f does not depend on rho (or
  /// `albedo` is false: a fluorescent lobe's albedo is the matrix's). `zero`: f is 0 with
  /// rho (its slope 1/rho is unbounded).
  float reflectanceLogSlope(const Vec3& wi, float rho, bool specular, bool albedo,
                            bool& zero) const {
    return visitScatteringModel(s_.material->kind, [&](auto model) {
      return decltype(model)::reflectanceLogSlope(s_, wi, rho, specular, albedo, zero);
    });
  }
  /// Density with which sample() returns wi through its non-specular lobes.
  float pdf(const Vec3& wi) const {
    return visitScatteringModel(s_.material->kind,
                                [&](auto model) { return decltype(model)::pdf(s_, wi); });
  }

  /// Draws a direction: uLobe picks the lobe, u the direction within it. Returns false when
  /// nothing is scattered (a black surface).
  bool sample(float uLobe, Sample2 u, BsdfSample& out) const {
    return visitScatteringModel(
        s_.material->kind, [&](auto model) { return decltype(model)::sample(s_, uLobe, u, out); });
  }

  /// Every delta lobe at once, each with its full weight (what Whitted ray tracing follows,
  /// instead of choosing one): reflection first, then transmission. Returns how many (0-2);
  /// glossy and diffuse lobes have none.
  int specularLobes(SpecularLobe (&out)[2]) const {
    return visitScatteringModel(
        s_.material->kind, [&](auto model) { return decltype(model)::specularLobes(s_, out); });
  }

  /// The shading normal on the side of wo (opaque models) or the outward one (dielectrics).
  const Vec3& normal() const { return s_.n; }

private:
  BsdfState s_;
};

} // namespace nx

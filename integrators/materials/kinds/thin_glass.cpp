// A thin glass wall (two parallel faces): Fresnel reflection with the internal reflections
// summed, straight transmission, no refraction offset: its parameters, build and sampling
// (below; dispatched from bsdf.cpp).

#include "integrators/materials/bsdf.h"
#include "integrators/materials/fresnel.h"
#include "integrators/materials/material_kind.h"

namespace nx {
namespace {

Material buildThinGlass(const MaterialKindSpec& kind, const ParameterSet& p,
                        const MaterialInputs& in) {
  Material m;
  m.kind = MaterialKind::ThinDielectric;
  const IorDesc* ior = p.get<IorDesc>("ior");
  m.ior = ior ? in.ior(*ior) : IorModel::constant(kind.numberDefault("ior"));
  setSurfaceReflectance(m, p, in, true, "transmission tint");
  return m;
}

constexpr KindParameter kParams[] = {
    {"color", "", ""}, {"reflectance", "1", "transmission tint"}, {"ior", "1.5", ""}};

constexpr std::pair<const char*, const char*> kRefusals[] = {
    {"alpha", "a thin wall stays smooth"},
    {"fluorescence", "fluorescent dielectrics need media: a <medium> with a dye"}};

} // namespace

extern const MaterialKindSpec kThinGlassKind{
    "thin_glass", "a thin glass wall: reflects and transmits straight through, without refraction",
    kParams, kRefusals, buildThinGlass};

// ---- evaluation (SurfaceBsdf's lobes of this kind) ----

// A thin glass wall: reflect with probability R(hero) (thinSlabReflectance), else pass straight
// through; lane i's weight is rho_i R_i / R_hero or rho_i (1 - R_i) / (1 - R_hero). The
// direction never depends on the wavelength, so dispersion needs no lane termination.
bool SurfaceBsdf::sampleThinDielectric(float uLobe, BsdfSample& out) const {
  const float c = std::abs(dot(wo_, n_));
  SampledSpectrum r;
  for (int i = 0; i < kLanes; ++i)
    r[i] = thinSlabReflectance(c, static_cast<float>(material_->ior.at((*lambda_).lambda[i])));
  out.pdf = 0;
  out.specular = true;
  out.terminateSecondary = false;
  out.eta = 1;
  const float rHero = r[0];
  const bool reflected = uLobe < rHero;
  out.straight = !reflected;
  out.wi = reflected ? reflect(wo_, dot(wo_, n_) > 0 ? n_ : -n_) : -wo_;
  const float p = reflected ? rHero : 1 - rHero;
  if (!(p > 0)) return false;
  for (int i = 0; i < kLanes; ++i) out.weight[i] = rho_[i] * (reflected ? r[i] : 1 - r[i]) / p;
  return true;
}

} // namespace nx

// A Lambertian base (possibly fluorescent) under a smooth clear coat of constant index, the
// internal reflections between them summed: its parameters, its build and its lobes
// (SurfaceBsdf's coat reflectance and coated sampling, below; dispatched from bsdf.cpp).

#include "core/error.h"
#include "integrators/materials/bsdf.h"
#include "integrators/materials/fresnel.h"
#include "integrators/materials/material_kind.h"
#include "integrators/sampling.h"

namespace nx {
namespace {

// The hemispherical (cosine-weighted) reflectance of a smooth interface of relative index n
// for diffuse light from inside: Fi = 1 - (1 - Fe) / n^2 with Fe = 2 integral_0^1 F(mu) mu dmu
// from outside (energy through the interface is the same both ways; radiance scales by n^2).
double internalDiffuseReflectance(double n) {
  double fe = 0;
  const int steps = 4000;
  for (int i = 0; i < steps; ++i) {
    const double mu = (i + 0.5) / steps;
    fe += 2 * fresnelDielectric(static_cast<float>(mu), static_cast<float>(n)) * mu / steps;
  }
  return 1 - (1 - fe) / (n * n);
}

Material buildCoated(const MaterialKindSpec& kind, const ParameterSet& p,
                     const MaterialInputs& in) {
  Material m;
  m.kind = MaterialKind::CoatedDiffuse;
  const IorDesc* ior = p.get<IorDesc>("ior");
  m.ior = ior ? in.ior(*ior) : IorModel::constant(kind.numberDefault("ior"));
  if (m.ior.dispersive())
    throw Error(ior->loc.str() + ": expected a constant <ior> for a coat (a number), found "
                                 "a dispersive one");
  m.coatInternalReflectance = static_cast<float>(internalDiffuseReflectance(m.ior.at(550)));
  setSurfaceReflectance(m, p, in, false, "reflectance");
  setFluorescence(m, p, in);
  return m;
}

constexpr KindParameter kParams[] = {{"color", "", ""},
                                     {"reflectance", "", "the base's albedo"},
                                     {"ior", "1.5", "the coat's index (a constant)"},
                                     {"fluorescence", "", "of the base"}};

constexpr std::pair<const char*, const char*> kRefusals[] = {
    {"roughness", "a Lambertian base under a smooth coat"},
    {"alpha", "its coat is smooth"},
    {"coating", "its coat is the clear coat; thin films lie on conductors and dielectrics"}};

} // namespace

extern const MaterialKindSpec kCoatedKind{
    "coated", "a Lambertian base under a smooth clear coat, internal reflections summed", kParams,
    kRefusals, buildCoated};

// ---- evaluation (SurfaceBsdf's lobes of this kind) ----

// A Lambertian base under a smooth, clear, non-dispersive coat (a plastic, a varnished or
// laminated sample): specular reflection F(o) at the coat, and light transmitted (1 - F(i))
// to the base, scattered with albedo rho, reflected back and forth between base and coat
// (the coat reflects the base's diffuse light with its internal hemispherical reflectance
// Fi = 1 - (1 - Fe) / n^2, Fe the external one), and transmitted out (1 - F(o)) / n^2:
//   f = F(o) delta + (1 - F(i)) (1 - F(o)) rho / (pi n^2 (1 - rho Fi))
// (the plastic model of Weidlich & Wilkie 2007 and Mitsuba's "plastic", derived in
// docs/materials.md). With rho = 1 it conserves energy exactly. A fluorescent base replaces
// rho by its re-radiation albedo; the internal reflections then use the base's elastic
// reflectance at the emitted wavelength.
float SurfaceBsdf::coatReflectance(float cosI) const {
  return fresnelDielectric(cosI, static_cast<float>(material_->ior.at(lambda_->lambda[0])));
}

// Specular with probability F(o), else a cosine-distributed diffuse direction: weights 1 and
// rho (1 - F(i)) / (n^2 (1 - rho Fi)) (f |cos| / pdf with pdf = (1 - F(o)) |cos| / pi).
bool SurfaceBsdf::sampleCoatedDiffuse(float uLobe, Sample2 u, BsdfSample& out) const {
  const float co = dot(wo_, n_);
  if (co <= 0) return false;
  const float fo = coatReflectance(co);
  out.terminateSecondary = false;
  out.eta = 1;
  if (uLobe < fo) {
    out.wi = reflect(wo_, n_);
    if (dot(out.wi, ng_) <= 0) return false;
    out.weight = SampledSpectrum::filled(1.0f);
    out.pdf = 0;
    out.specular = true;
    return true;
  }
  const Frame frame = Frame::fromNormal(n_);
  const Vec3 local = sampleCosineHemisphere(u);
  if (local.z <= 0) return false;
  out.wi = frame.toWorld(local);
  if (dot(out.wi, ng_) <= 0) return false;
  out.pdf = (1 - fo) * cosineHemispherePdf(local.z);
  out.specular = false;
  const float n = static_cast<float>(material_->ior.at(lambda_->lambda[0]));
  const float t = (1 - coatReflectance(local.z)) / (n * n);
  for (int i = 0; i < kLanes; ++i)
    out.diffuseScale[i] = t / (1 - rho_[i] * material_->coatInternalReflectance);
  out.weight = rho_ * out.diffuseScale;
  return true;
}

} // namespace nx

// A Lambertian base (possibly fluorescent) under a smooth clear coat of constant index, the
// internal reflections between them summed: its parameters, its build and its lobes
// (its scattering model, below).

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

constexpr const char* kExamples[] = {"<ior>1.5</ior><reflectance>1</reflectance>",
                                     "<ior>1.9</ior><reflectance>0.5</reflectance>"};

} // namespace

extern const MaterialKindSpec kCoatedKind{
    "coated",    "a Lambertian base under a smooth clear coat, internal reflections summed",
    kParams,     kRefusals,
    buildCoated, kExamples};

// ---- the scattering model (ScatteringModel<CoatedDiffuse>) ----
//
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

using Coated = ScatteringModel<MaterialKind::CoatedDiffuse>;

namespace {

// The clear coat's Fresnel reflectance from outside at cosine cosI.
float coatReflectance(const BsdfState& s, float cosI) {
  return fresnelDielectric(cosI, static_cast<float>(s.material->ior.at(s.lambda->lambda[0])));
}

} // namespace

template <>
uint8_t Coated::lobes(const Material&) {
  return kSpecularReflection | kDiffuseReflection;
}

template <>
void Coated::prepare(BsdfState& s) {
  s.faceWo();
}

template <>
SampledSpectrum Coated::diffuseLobe(const BsdfState& s, const Vec3& wi) {
  const float ci = dot(wi, s.n), co = dot(s.wo, s.n);
  if (ci <= 0 || co <= 0 || dot(wi, s.ng) <= 0) return {};
  // (1 - F(i)) (1 - F(o)) |cos i| / (pi n^2 (1 - rho Fi)): transmitted in, scattered by the
  // base, reflected between base and coat (Fi the coat's internal diffuse reflectance), out.
  const float n = static_cast<float>(s.material->ior.at(s.lambda->lambda[0]));
  const float t = (1 - coatReflectance(s, ci)) * (1 - coatReflectance(s, co)) * ci *
                  static_cast<float>(kInvPi) / (n * n);
  SampledSpectrum f;
  for (int i = 0; i < kLanes; ++i) f[i] = t / (1 - s.rho[i] * s.material->coatInternalReflectance);
  return f;
}

template <>
SampledSpectrum Coated::f(const BsdfState& s, const Vec3& wi) {
  return s.rho * diffuseLobe(s, wi);
}

template <>
float Coated::pdf(const BsdfState& s, const Vec3& wi) {
  const float co = dot(s.wo, s.n);
  if (co <= 0) return 0;
  return (1 - coatReflectance(s, co)) * cosineHemispherePdf(dot(wi, s.n));
}

// Specular with probability F(o), else a cosine-distributed diffuse direction: weights 1 and
// rho (1 - F(i)) / (n^2 (1 - rho Fi)) (f |cos| / pdf with pdf = (1 - F(o)) |cos| / pi).
template <>
bool Coated::sample(const BsdfState& s, float uLobe, Sample2 u, BsdfSample& out) {
  const float co = dot(s.wo, s.n);
  if (co <= 0) return false;
  const float fo = coatReflectance(s, co);
  out.terminateSecondary = false;
  out.eta = 1;
  if (uLobe < fo) {
    out.wi = reflect(s.wo, s.n);
    if (dot(out.wi, s.ng) <= 0) return false;
    out.weight = SampledSpectrum::filled(1.0f);
    out.pdf = 0;
    out.specular = true;
    return true;
  }
  const Frame frame = Frame::fromNormal(s.n);
  const Vec3 local = sampleCosineHemisphere(u);
  if (local.z <= 0) return false;
  out.wi = frame.toWorld(local);
  if (dot(out.wi, s.ng) <= 0) return false;
  out.pdf = (1 - fo) * cosineHemispherePdf(local.z);
  out.specular = false;
  const float n = static_cast<float>(s.material->ior.at(s.lambda->lambda[0]));
  const float t = (1 - coatReflectance(s, local.z)) / (n * n);
  for (int i = 0; i < kLanes; ++i)
    out.diffuseScale[i] = t / (1 - s.rho[i] * s.material->coatInternalReflectance);
  out.weight = s.rho * out.diffuseScale;
  return true;
}

template <>
int Coated::specularLobes(const BsdfState& s, SpecularLobe (&out)[2]) {
  const float c = dot(s.wo, s.n);
  if (c <= 0) return 0;
  out[0] = {reflect(s.wo, s.n), SampledSpectrum::filled(coatReflectance(s, c)), false};
  return 1;
}

// Its diffuse lobe rho t / (1 - rho F_i) gives 1/rho + F_i / (1 - rho F_i); its coat's
// reflection does not depend on rho.
template <>
float Coated::reflectanceLogSlope(const BsdfState& s, const Vec3&, float rho, bool specular,
                                  bool albedo, bool& zero) {
  zero = false;
  if (specular) return 0.0f;
  const float fi = s.material->coatInternalReflectance;
  return inverseReflectanceSlope(rho, albedo, zero) + fi / (1 - rho * fi);
}

template <>
bool Coated::roughnessLogSlopes(const BsdfState&, const Vec3&, float&, float&) {
  return false;
}

template <>
BsdfDerivativeSteps Coated::derivativeSteps(const Material&) {
  return {};
}

template <>
SampledSpectrum Coated::straightTransmittance(const Material&, const SampledWavelengths&, float) {
  return {};
}

template <>
bool Coated::albedoIsReflectance(const Material&) {
  return false;
}

template <>
bool Coated::roughnessDifferentiable(const Material&) {
  return false;
}

} // namespace nx

// Niixtracer's surfaces: (1 - r) rho * ideal mirror + r rho / pi, one model under six names that
// differ in their default r (matte, diffuse and default 1, plastic 0.7, metal 0.3, mirror 0),
// made energy-conserving (each lobe drawn with its weight; docs/materials.md): their
// parameters, build and sampling (below; dispatched by SurfaceBsdf).

#include "integrators/materials/bsdf.h"
#include "integrators/materials/fresnel.h"
#include "integrators/materials/material_kind.h"
#include "integrators/sampling.h"

namespace nx {
namespace {

Material buildMixture(const MaterialKindSpec& kind, const ParameterSet& p,
                      const MaterialInputs& in) {
  Material m;
  m.kind = MaterialKind::Mixture;
  m.roughness = static_cast<float>(p.number("roughness").value_or(kind.numberDefault("roughness")));
  setSurfaceReflectance(m, p, in, false, "reflectance");
  setFluorescence(m, p, in);
  return m;
}

#define NX_MIXTURE_PARAMS(roughness)                                                               \
  {"color", "", ""}, {"reflectance", "", "albedo rho (required unless the object emits)"},         \
      {"roughness", roughness, ""}, {                                                              \
    "fluorescence", "", ""                                                                         \
  }

constexpr KindParameter kMatteParams[] = {NX_MIXTURE_PARAMS("1")};
constexpr KindParameter kPlasticParams[] = {NX_MIXTURE_PARAMS("0.7")};
constexpr KindParameter kMetalParams[] = {NX_MIXTURE_PARAMS("0.3")};
constexpr KindParameter kMirrorParams[] = {NX_MIXTURE_PARAMS("0")};
#undef NX_MIXTURE_PARAMS

constexpr std::pair<const char*, const char*> kRefusals[] = {
    {"alpha", "GGX roughness is for conductors and dielectrics; here <roughness> weighs the "
              "Lambertian lobe"},
    {"ior", "an index of refraction is for dielectrics and coated"},
    {"coating", "thin films lie on conductors and smooth dielectrics"}};

constexpr const char* kMatteExamples[] = {"<reflectance>0.9</reflectance>"};

constexpr const char* kPlasticExamples[] = {
    "<roughness>0.4</roughness><reflectance>1</reflectance>"};

constexpr const char* kMirrorExamples[] = {"<reflectance>1</reflectance>"};

} // namespace

extern const MaterialKindSpec kMatteKind{
    "matte",      "Lambertian (Niixtracer's mixture with r = 1)",
    kMatteParams, kRefusals,
    buildMixture, kMatteExamples};
extern const MaterialKindSpec kDiffuseKind{"diffuse", "the same as matte", kMatteParams,
                                           kRefusals, buildMixture,        {}};
extern const MaterialKindSpec kDefaultKind{"default", "the same as matte", kMatteParams,
                                           kRefusals, buildMixture,        {}};
extern const MaterialKindSpec kPlasticKind{
    "plastic",      "Niixtracer's mixture with r = 0.7: mostly diffuse, some mirror",
    kPlasticParams, kRefusals,
    buildMixture,   kPlasticExamples};
extern const MaterialKindSpec kMetalKind{
    "metal",
    "Niixtracer's mixture with r = 0.3: mostly mirror, tinted by rho (physical metals: conductor)",
    kMetalParams,
    kRefusals,
    buildMixture,
    {}};
extern const MaterialKindSpec kMirrorKind{
    "mirror",      "an ideal mirror tinted by rho (the mixture with r = 0)",
    kMirrorParams, kRefusals,
    buildMixture,  kMirrorExamples};

// ---- the scattering model (ScatteringModel<Mixture>) ----

using Mixture = ScatteringModel<MaterialKind::Mixture>;

namespace {

// r |cos(wi)| / pi: the diffuse lobe without its albedo (fluorescent lobes supply their own).
float diffuseFactor(const BsdfState& s, const Vec3& wi) {
  if (!(s.material->roughness > 0)) return 0;
  const float c = dot(wi, s.n);
  if (c <= 0 || dot(s.wo, s.n) <= 0 || dot(wi, s.ng) <= 0) return 0;
  return s.material->roughness * static_cast<float>(kInvPi) * c;
}

} // namespace

template <>
uint8_t Mixture::lobes(const Material& m) {
  const float r = m.roughness;
  return static_cast<uint8_t>((r > 0 ? kDiffuseReflection : 0) | (r < 1 ? kSpecularReflection : 0));
}

template <>
void Mixture::prepare(BsdfState& s) {
  s.faceWo();
}

template <>
SampledSpectrum Mixture::f(const BsdfState& s, const Vec3& wi) {
  return s.rho * diffuseFactor(s, wi);
}

template <>
SampledSpectrum Mixture::diffuseLobe(const BsdfState& s, const Vec3& wi) {
  return SampledSpectrum::filled(diffuseFactor(s, wi));
}

template <>
float Mixture::pdf(const BsdfState& s, const Vec3& wi) {
  if (!(s.material->roughness > 0) || dot(s.wo, s.n) <= 0) return 0;
  return s.material->roughness * cosineHemispherePdf(dot(wi, s.n));
}

// (1 - r) rho * mirror + r rho / pi, lobe chosen with probabilities 1 - r and r: either way
// the weight is rho (Niixtracer's "roughness" mixture, made energy-conserving).
template <>
bool Mixture::sample(const BsdfState& s, float uLobe, Sample2 u, BsdfSample& out) {
  if (dot(s.wo, s.n) <= 0) return false;
  const float r = s.material->roughness;
  if (uLobe < r) {
    const Frame frame = Frame::fromNormal(s.n);
    const Vec3 local = sampleCosineHemisphere(u);
    if (local.z <= 0) return false;
    out.wi = frame.toWorld(local);
    out.pdf = r * cosineHemispherePdf(local.z);
    out.specular = false;
  } else {
    out.wi = reflect(s.wo, s.n);
    out.pdf = 0;
    out.specular = true;
  }
  // A direction the shading frame allows below the geometric surface is absorbed.
  if (dot(out.wi, s.ng) <= 0) return false;
  out.weight = s.rho;
  out.terminateSecondary = false;
  out.eta = 1;
  return true;
}

template <>
int Mixture::specularLobes(const BsdfState& s, SpecularLobe (&out)[2]) {
  if (!(s.material->roughness < 1) || dot(s.wo, s.n) <= 0) return 0;
  out[0] = {reflect(s.wo, s.n), s.rho * (1 - s.material->roughness), false};
  return 1;
}

// Both lobes are rho times a shape: 1 / rho.
template <>
float Mixture::reflectanceLogSlope(const BsdfState&, const Vec3&, float rho, bool, bool albedo,
                                   bool& zero) {
  return inverseReflectanceSlope(rho, albedo, zero);
}

template <>
bool Mixture::roughnessLogSlopes(const BsdfState&, const Vec3&, float&, float&) {
  return false; // r weighs two lobes; it is not differentiated
}

template <>
BsdfDerivativeSteps Mixture::derivativeSteps(const Material&) {
  return {};
}

template <>
SampledSpectrum Mixture::straightTransmittance(const Material&, const SampledWavelengths&, float) {
  return {};
}

// Both lobes reflect rho in all: (1 - r) rho + r rho.
template <>
bool Mixture::albedoIsReflectance(const Material&) {
  return true;
}

template <>
bool Mixture::roughnessDifferentiable(const Material&) {
  return false;
}

} // namespace nx

// A thin glass wall (two parallel faces): Fresnel reflection with the internal reflections
// summed, straight transmission, no refraction offset: its parameters, build and sampling
// (its scattering model, below).

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

constexpr const char* kExamples[] = {"<ior>1.5</ior>"};

} // namespace

extern const MaterialKindSpec kThinGlassKind{
    "thin_glass",
    "a thin glass wall: reflects and transmits straight through, without refraction",
    kParams,
    kRefusals,
    buildThinGlass,
    kExamples};

// ---- the scattering model (ScatteringModel<ThinDielectric>) ----

using ThinWall = ScatteringModel<MaterialKind::ThinDielectric>;

template <>
uint8_t ThinWall::lobes(const Material&) {
  return kSpecularReflection | kSpecularTransmission | kStraightTransmission;
}

template <>
void ThinWall::prepare(BsdfState&) {} // either side: the outward normal stays

template <>
SampledSpectrum ThinWall::f(const BsdfState&, const Vec3&) {
  return {};
}

template <>
SampledSpectrum ThinWall::diffuseLobe(const BsdfState&, const Vec3&) {
  return {};
}

template <>
float ThinWall::pdf(const BsdfState&, const Vec3&) {
  return 0;
}

// A thin glass wall: reflect with probability R(hero) (thinSlabReflectance), else pass straight
// through; lane i's weight is rho_i R_i / R_hero or rho_i (1 - R_i) / (1 - R_hero). The
// direction never depends on the wavelength, so dispersion needs no lane termination.
template <>
bool ThinWall::sample(const BsdfState& s, float uLobe, Sample2, BsdfSample& out) {
  const float c = std::abs(dot(s.wo, s.n));
  SampledSpectrum r;
  for (int i = 0; i < kLanes; ++i)
    r[i] = thinSlabReflectance(c, static_cast<float>(s.material->ior.at(s.lambda->lambda[i])));
  out.pdf = 0;
  out.specular = true;
  out.terminateSecondary = false;
  out.eta = 1;
  const float rHero = r[0];
  const bool reflected = uLobe < rHero;
  out.straight = !reflected;
  out.wi = reflected ? reflect(s.wo, dot(s.wo, s.n) > 0 ? s.n : -s.n) : -s.wo;
  const float p = reflected ? rHero : 1 - rHero;
  if (!(p > 0)) return false;
  for (int i = 0; i < kLanes; ++i) out.weight[i] = s.rho[i] * (reflected ? r[i] : 1 - r[i]) / p;
  return true;
}

template <>
int ThinWall::specularLobes(const BsdfState& s, SpecularLobe (&out)[2]) {
  const float c = dot(s.wo, s.n);
  const float ac = std::abs(c);
  SampledSpectrum r, t;
  for (int i = 0; i < kLanes; ++i) {
    r[i] = thinSlabReflectance(ac, static_cast<float>(s.material->ior.at(s.lambda->lambda[i])));
    t[i] = 1 - r[i];
  }
  out[0] = {reflect(s.wo, c > 0 ? s.n : -s.n), s.rho * r, false};
  out[1] = {-s.wo, s.rho * t, false};
  return 2;
}

// rho is a transmission tint: both lobes are linear in it.
template <>
float ThinWall::reflectanceLogSlope(const BsdfState&, const Vec3&, float rho, bool, bool albedo,
                                    bool& zero) {
  return inverseReflectanceSlope(rho, albedo, zero);
}

template <>
bool ThinWall::roughnessLogSlopes(const BsdfState&, const Vec3&, float&, float&) {
  return false;
}

template <>
BsdfDerivativeSteps ThinWall::derivativeSteps(const Material&) {
  return {};
}

// A thin wall lets 1 - R through, tinted by its transmission colour.
template <>
SampledSpectrum ThinWall::straightTransmittance(const Material& m, const SampledWavelengths& lambda,
                                                float cosine) {
  SampledSpectrum tint;
  m.reflectance.evaluate(lambda, tint);
  SampledSpectrum t;
  for (int i = 0; i < kLanes; ++i)
    t[i] =
        tint[i] * (1 - thinSlabReflectance(cosine, static_cast<float>(m.ior.at(lambda.lambda[i]))));
  return t;
}

template <>
bool ThinWall::albedoIsReflectance(const Material&) {
  return false;
}

template <>
bool ThinWall::roughnessDifferentiable(const Material&) {
  return false;
}

} // namespace nx

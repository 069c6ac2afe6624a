// The boundary of a medium with the same index on both sides: light passes unchanged (no
// reflection, no refraction): its parameters, build and scattering model (one lobe, straight on).

#include "core/error.h"
#include "integrators/materials/material_kind.h"
#include "integrators/materials/scattering_model.h"

namespace nx {
namespace {

Material buildInterface(const MaterialKindSpec&, const ParameterSet&, const MaterialInputs& in) {
  if (in.emitter)
    throw Error(in.objectLoc.str() +
                ": expected no <emission> on an interface (it only bounds a medium), found one");
  Material m;
  m.kind = MaterialKind::Interface;
  m.reflectance = Spectrum(ConstantSpectrum{1.0});
  return m;
}

constexpr std::pair<const char*, const char*> kRefusals[] = {
    {"color", "it only bounds a medium"},
    {"reflectance", "it only bounds a medium"},
    {"fluorescence", "it only bounds a medium"}};

constexpr const char* kExamples[] = {"<medium><sigma_a>0.1</sigma_a><sigma_s>0</sigma_s></medium>"};

} // namespace

extern const MaterialKindSpec kInterfaceKind{
    "interface",
    "an index-matched boundary of a <medium>: light passes unchanged",
    {},
    kRefusals,
    buildInterface,
    kExamples};

// ---- the scattering model (ScatteringModel<Interface>) ----

using Interface = ScatteringModel<MaterialKind::Interface>;

template <>
uint8_t Interface::lobes(const Material&) {
  return kSpecularTransmission | kStraightTransmission;
}

template <>
void Interface::prepare(BsdfState&) {}

template <>
SampledSpectrum Interface::f(const BsdfState&, const Vec3&) {
  return {};
}

template <>
SampledSpectrum Interface::diffuseLobe(const BsdfState&, const Vec3&) {
  return {};
}

template <>
float Interface::pdf(const BsdfState&, const Vec3&) {
  return 0;
}

// Index-matched: the path continues straight on, every lane unchanged.
template <>
bool Interface::sample(const BsdfState& s, float, Sample2, BsdfSample& out) {
  out.wi = -s.wo;
  out.weight = SampledSpectrum::filled(1.0f);
  out.pdf = 0;
  out.specular = true;
  out.terminateSecondary = false;
  out.eta = 1;
  out.straight = true;
  return true;
}

template <>
int Interface::specularLobes(const BsdfState& s, SpecularLobe (&out)[2]) {
  out[0] = {-s.wo, SampledSpectrum::filled(1.0f), false};
  return 1;
}

// Light passes unchanged: nothing depends on rho.
template <>
float Interface::reflectanceLogSlope(const BsdfState&, const Vec3&, float, bool, bool, bool& zero) {
  zero = false;
  return 0.0f;
}

template <>
bool Interface::roughnessLogSlopes(const BsdfState&, const Vec3&, float&, float&) {
  return false;
}

template <>
BsdfDerivativeSteps Interface::derivativeSteps(const Material&) {
  return {};
}

template <>
SampledSpectrum Interface::straightTransmittance(const Material&, const SampledWavelengths&,
                                                 float) {
  return SampledSpectrum::filled(1.0f);
}

template <>
bool Interface::albedoIsReflectance(const Material&) {
  return false;
}

template <>
bool Interface::roughnessDifferentiable(const Material&) {
  return false;
}

} // namespace nx

// A metal: GGX microfacets (smooth when alpha is 0) with the exact Fresnel reflectance of its
// complex index eta + i k, a built-in measured metal or given spectra, optionally under a thin
// film on each microfacet: its parameters, its build and its lobes (its scattering model,
// below).

#include <tuple>

#include "core/error.h"
#include "core/text_table.h"
#include "integrators/materials/bsdf.h"
#include "integrators/materials/fresnel.h"
#include "integrators/materials/material_kind.h"
#include "spectra/metals.h"
#include "spectra/spectrum_bounds.h"

namespace nx {
namespace {

std::string metalList() {
  std::string names;
  for (const std::string& n : metalNames()) names += (names.empty() ? "" : ", ") + n;
  return names;
}

Material buildConductor(const MaterialKindSpec&, const ParameterSet& p, const MaterialInputs& in) {
  Material m;
  m.kind = MaterialKind::Conductor;
  m.reflectance = Spectrum(ConstantSpectrum{1.0});
  const SpectrumDesc *eta = p.get<SpectrumDesc>("eta"), *k = p.get<SpectrumDesc>("k");
  if (const Parameter* metalParam = p.find("metal")) {
    if (eta || k)
      throw Error(metalParam->loc.str() + ": expected either <metal> or <eta> and <k>, found both");
    const std::string& name = std::get<std::string>(metalParam->value);
    const std::optional<MetalIndex> metal = namedMetal(name);
    if (!metal)
      throw Error(metalParam->loc.str() + ": expected a metal name (" + metalList() + "), found '" +
                  name + "'");
    // Indexed for the render loop's lookups (the same values, found without a binary search).
    m.conductorEta = forRendering(metal->eta);
    m.conductorK = forRendering(metal->k);
  } else {
    if (!eta || !k)
      throw Error(in.objectLoc.str() + ": expected <metal> (" + metalList() +
                  ") or both <eta> and <k> on a conductor, found " +
                  (eta ? "<eta> alone"
                   : k ? "<k> alone"
                       : "neither"));
    m.conductorEta = forRendering(in.spectrum(*eta, SpectrumRole::Coefficient));
    m.conductorK = forRendering(in.spectrum(*k, SpectrumRole::Coefficient));
    for (const auto& [sp, desc, what, lo] :
         {std::tuple{&m.conductorEta, eta, "eta", 1e-3}, std::tuple{&m.conductorK, k, "k", 0.0}}) {
      const SpectrumExtremes e = spectrumExtremes(*sp, kTraceMinNm, kTraceMaxNm);
      if (!(e.min >= lo && e.max <= 1e3))
        throw Error(desc->loc.str() + ": expected " + what + " within [" + numberText(lo) +
                    ", 1000] at every wavelength of " + tracedRange() + ", found " +
                    (std::isnan(e.min) ? std::string("a non-finite value")
                                       : numberText(e.min < lo ? e.min : e.max) + " at " +
                                             numberText(e.min < lo ? e.minNm : e.maxNm) + " nm") +
                    (e.min == 0 && lo > 0 ? " (a table is 0 beyond its rows; extrapolate=\"hold\" "
                                            "keeps its end values)"
                                          : ""));
    }
  }
  setGgxAlpha(m, p);
  setCoating(m, p, in);
  return m;
}

constexpr KindParameter kParams[] = {{"metal", "", "a built-in metal (or <eta> and <k>)"},
                                     {"eta", "", "with <k>, instead of <metal>"},
                                     {"k", "", "with <eta>, instead of <metal>"},
                                     {"alpha", "0", "GGX roughness (0: smooth)"},
                                     {"alpha_u", "", ""},
                                     {"alpha_v", "", ""},
                                     {"coating", "", "a thin film on each microfacet"}};

constexpr std::pair<const char*, const char*> kRefusals[] = {
    {"color", "its colour is its <metal> or <eta> and <k>"},
    {"reflectance", "its colour is its <metal> or <eta> and <k>"},
    {"roughness", "its roughness is <alpha>"},
    {"ior", "its index is <eta> and <k>"}};

constexpr const char* kExamples[] = {
    "<metal>gold</metal>", "<metal>aluminium</metal><alpha>0.2</alpha>",
    "<metal>silver</metal><alpha_u>0.05</alpha_u><alpha_v>0.4</alpha_v>",
    "<metal>gold</metal><alpha>0.01</alpha>"};

} // namespace

extern const MaterialKindSpec kConductorKind{
    "conductor",    "a metal: GGX microfacets and the exact Fresnel reflectance of eta + i k",
    kParams,        kRefusals,
    buildConductor, kExamples};

// ---- the scattering model (ScatteringModel<Conductor>) ----

using Conductor = ScatteringModel<MaterialKind::Conductor>;

namespace {

bool smooth(const BsdfState& s) {
  return !(std::max(s.alpha.ax, s.alpha.ay) > 0);
}

// The lanes' Fresnel reflectance at a micro-surface seen with cosine cosI (through the
// coating: a thin film on each microfacet).
SampledSpectrum conductorFresnel(const BsdfState& s, float cosI) {
  SampledSpectrum f;
  const Material& m = *s.material;
  if (m.coatingNm > 0) {
    for (int i = 0; i < kLanes; ++i) {
      const float nm = s.lambda->lambda[i];
      f[i] = thinFilmReflectance(cosI, 1.0f, static_cast<float>(m.coatingIor.at(nm)), s.eta[i],
                                 s.k[i], m.coatingNm, nm);
    }
    return f;
  }
  for (int i = 0; i < kLanes; ++i) f[i] = fresnelConductor(cosI, s.eta[i], s.k[i]);
  return f;
}

} // namespace

template <>
uint8_t Conductor::lobes(const Material& m) {
  return roughMicrofacets(m) ? kGlossyReflection : kSpecularReflection;
}

template <>
void Conductor::prepare(BsdfState& s) {
  s.faceWo();
  s.material->conductorEta.evaluate(*s.lambda, s.eta);
  s.material->conductorK.evaluate(*s.lambda, s.k);
  s.alpha = clampedGgx(*s.material);
  s.frame = Frame::fromNormal(s.n);
}

// Torrance-Sparrow with GGX: f cos(wi) = D(h) G2(wo, wi) F(wo.h) / (4 cos(wo)), h the half
// vector (Walter et al. 2007, eq. 20); zero below the surface (either normal).
template <>
SampledSpectrum Conductor::f(const BsdfState& s, const Vec3& wi) {
  if (smooth(s) || dot(wi, s.ng) <= 0) return {};
  const Vec3 o = s.frame.toLocal(s.wo), i = s.frame.toLocal(wi);
  if (o.z <= 0 || i.z <= 0) return {};
  const Vec3 h = normalize(o + i);
  const float d = s.alpha.d(h);
  if (!(d > 0)) return {};
  return conductorFresnel(s, dot(o, h)) * (d * s.alpha.g2(o, i) / (4 * o.z));
}

template <>
SampledSpectrum Conductor::diffuseLobe(const BsdfState&, const Vec3&) {
  return {};
}

template <>
float Conductor::pdf(const BsdfState& s, const Vec3& wi) {
  if (smooth(s) || dot(wi, s.ng) <= 0) return 0;
  const Vec3 o = s.frame.toLocal(s.wo), i = s.frame.toLocal(wi);
  if (o.z <= 0 || i.z <= 0) return 0;
  const Vec3 h = normalize(o + i);
  return s.alpha.g1(o) * s.alpha.d(h) / (4 * o.z);
}

// Visible-normal sampling: h from D_wo, wi = reflect(wo, h); the weight f cos / pdf is
// F G2 / G1(wo) with pdf = G1(wo) D(h) / (4 cos(wo)) (Heitz 2018, sec. 2). A reflection below
// the surface is lost (the single-scattering model's energy loss, docs/materials.md).
template <>
bool Conductor::sample(const BsdfState& s, float, Sample2 u, BsdfSample& out) {
  const float cosO = dot(s.wo, s.n);
  if (cosO <= 0) return false;
  out.terminateSecondary = false;
  out.eta = 1;
  if (smooth(s)) {
    out.wi = reflect(s.wo, s.n);
    if (dot(out.wi, s.ng) <= 0) return false;
    out.weight = conductorFresnel(s, cosO);
    out.pdf = 0;
    out.specular = true;
    return true;
  }
  const Vec3 o = s.frame.toLocal(s.wo);
  const Vec3 h = s.alpha.sampleVisibleNormal(o, u);
  const float oh = dot(o, h);
  if (!(oh > 0)) return false;
  const Vec3 i = h * (2 * oh) - o;
  if (i.z <= 0) return false;
  out.wi = s.frame.toWorld(i);
  if (dot(out.wi, s.ng) <= 0) return false;
  out.pdf = s.alpha.g1(o) * s.alpha.d(h) / (4 * o.z);
  if (!(out.pdf > 0)) return false;
  out.weight = conductorFresnel(s, oh) * (s.alpha.g2(o, i) / s.alpha.g1(o));
  out.specular = false;
  return true;
}

template <>
int Conductor::specularLobes(const BsdfState& s, SpecularLobe (&out)[2]) {
  BsdfSample bs;
  if (!smooth(s) || !sample(s, 0, {}, bs)) return 0;
  out[0] = {bs.wi, bs.weight, false};
  return 1;
}

// Its reflectance is its complex index's: rho does not enter.
template <>
float Conductor::reflectanceLogSlope(const BsdfState&, const Vec3&, float, bool, bool, bool& zero) {
  zero = false;
  return 0.0f;
}

template <>
bool Conductor::roughnessLogSlopes(const BsdfState& s, const Vec3& wi, float& dAlphaU,
                                   float& dAlphaV) {
  if (smooth(s)) return false;
  const Vec3 o = s.frame.toLocal(s.wo), i = s.frame.toLocal(wi);
  if (o.z <= 0 || i.z <= 0) return false;
  s.alpha.logDerivatives(o, i, dAlphaU, dAlphaV);
  return std::isfinite(dAlphaU) && std::isfinite(dAlphaV);
}

template <>
BsdfDerivativeSteps Conductor::derivativeSteps(const Material& m) {
  return microfacetDerivativeSteps(m);
}

template <>
SampledSpectrum Conductor::straightTransmittance(const Material&, const SampledWavelengths&,
                                                 float) {
  return {};
}

template <>
bool Conductor::albedoIsReflectance(const Material&) {
  return false;
}

// Its roughness is differentiated where its lobe is a microfacet lobe on both axes (from a
// smooth metal's delta lobe there is no derivative to follow).
template <>
bool Conductor::roughnessDifferentiable(const Material& m) {
  return m.alphaU > 0 && m.alphaV > 0;
}

} // namespace nx

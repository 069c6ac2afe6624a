// Dielectrics: exact Fresnel reflection and refraction with total internal reflection, smooth
// or rough (GGX microfacets, Walter et al. 2007), dispersive through a Cauchy or Sellmeier
// index, optionally under a thin-film coating (smooth only). Four names differing in their
// default index: their parameters, build and lobes (the smooth Fresnel split and the rough
// microfacet lobes: its scattering model, below).

#include <algorithm>

#include "core/error.h"
#include "integrators/materials/bsdf.h"
#include "integrators/materials/fresnel.h"
#include "integrators/materials/material_kind.h"

namespace nx {
namespace {

Material buildDielectric(const MaterialKindSpec& kind, const ParameterSet& p,
                         const MaterialInputs& in) {
  Material m;
  m.kind = MaterialKind::Dielectric;
  const IorDesc* ior = p.get<IorDesc>("ior");
  m.ior = ior ? in.ior(*ior) : IorModel::constant(kind.numberDefault("ior"));
  setGgxAlpha(m, p);
  setSurfaceReflectance(m, p, in, true, "transmission tint");
  if (const Parameter* c = p.find("coating")) {
    // A thin film needs a smooth interface to lie on.
    if (std::max(m.alphaU, m.alphaV) > 0)
      throw Error(c->loc.str() +
                  ": expected a <coating> on a smooth dielectric, found it on a rough one "
                  "(<alpha>)");
    setCoating(m, p, in);
  }
  return m;
}

#define NX_DIELECTRIC_PARAMS(ior)                                                                  \
  {"color", "", ""}, {"reflectance", "1", "transmission tint"}, {"ior", ior, ""},                  \
      {"alpha", "0", "GGX roughness (0: smooth; a frosted surface above)"}, {"alpha_u", "", ""},   \
      {"alpha_v", "", ""}, {                                                                       \
    "coating", "", "a thin film on a smooth surface"                                               \
  }

constexpr KindParameter kGlassParams[] = {NX_DIELECTRIC_PARAMS("1.5")};
constexpr KindParameter kDiamondParams[] = {NX_DIELECTRIC_PARAMS("2.418")};
constexpr KindParameter kTranslucentParams[] = {NX_DIELECTRIC_PARAMS("1.02")};
#undef NX_DIELECTRIC_PARAMS

constexpr std::pair<const char*, const char*> kRefusals[] = {
    {"fluorescence", "fluorescent dielectrics need media: a <medium> with a dye"},
    {"roughness", "a dielectric's roughness is <alpha>"}};

constexpr const char* kGlassExamples[] = {
    "<ior>1.5</ior>", "<ior>bk7</ior>", "<ior>bk7</ior><alpha>0.3</alpha>",
    "<ior>2.4</ior><alpha>0.05</alpha>", "<ior>1.5</ior><alpha>0.01</alpha>"};

constexpr const char* kDiamondExamples[] = {"<alpha>0.1</alpha>"};

} // namespace

extern const MaterialKindSpec kGlassKind{
    "glass",         "a dielectric of index 1.5 unless <ior> says otherwise",
    kGlassParams,    kRefusals,
    buildDielectric, kGlassExamples};
extern const MaterialKindSpec kDiamondKind{"diamond",       "a dielectric of index 2.418",
                                           kDiamondParams,  kRefusals,
                                           buildDielectric, kDiamondExamples};
extern const MaterialKindSpec kTranslucentKind{
    "translucent",      "a dielectric of index 1.02 (Niixtracer's)",
    kTranslucentParams, kRefusals,
    buildDielectric,    {}};
extern const MaterialKindSpec kTransparentKind{
    "transparent", "the same as translucent", kTranslucentParams, kRefusals, buildDielectric, {}};

// ---- the scattering model (ScatteringModel<Dielectric>) ----

using Dielectric = ScatteringModel<MaterialKind::Dielectric>;

namespace {

bool rough(const BsdfState& s) {
  return std::max(s.alpha.ax, s.alpha.ay) > 0;
}

// Reflectance of a smooth dielectric interface for light arriving with cosine cosI from the
// side of index nIncident towards nTransmitted (absolute indices), through the material's
// thin-film coating if it has one (on the outside of the surface), at wavelength lambdaNm.
float dielectricReflectance(const Material& m, float cosI, float nIncident, float nTransmitted,
                            float lambdaNm) {
  if (!(m.coatingNm > 0)) return fresnelDielectric(cosI, nTransmitted / nIncident);
  return thinFilmReflectance(cosI, nIncident, static_cast<float>(m.coatingIor.at(lambdaNm)),
                             nTransmitted, 0.0f, m.coatingNm, lambdaNm);
}

// Smooth dielectric: reflect with probability F(hero), else refract (Snell); total internal
// reflection when there is no refracted direction. Lane i's weight is F_i / F_hero after a
// reflection and, through a non-dispersive interface, (1 - F_i) / (1 - F_hero) after a
// refraction. Through a dispersive interface the refracted direction is the hero's alone:
// the sample asks to terminate the secondaries (their weight is 0 here; the integrator makes
// the hero's estimator stand alone from this vertex on, see heroOnly()). Unbiased: given the
// lanes' wavelengths, lane i's expected weight is F_i R_i + [i = 0] (1 - F_0) T_0 kLanes, and
// with every lane's marginal density the same, the lanes' sum estimates the integral of
// F R + (1 - F) T (docs/rendering.md, "Dispersion").
bool sampleSmooth(const BsdfState& s, float uLobe, BsdfSample& out) {
  const float cosO = dot(s.wo, s.n);
  const bool entering = cosO > 0;
  const Vec3 n = entering ? s.n : -s.n;
  const float c = std::abs(cosO);
  const bool dispersive = s.material->ior.dispersive();
  const bool coated = s.material->coatingNm > 0; // reflectance varies with the wavelength
  SampledSpectrum eta, fresnel;
  for (int i = 0; i < kLanes; ++i) {
    const float ior = static_cast<float>(s.material->ior.at((*s.lambda).lambda[i]));
    eta[i] = entering ? ior : 1.0f / ior; // n_transmitted / n_incident
    fresnel[i] = coated ? dielectricReflectance(*s.material, c, entering ? 1.0f : ior,
                                                entering ? ior : 1.0f, (*s.lambda).lambda[i])
                        : fresnelDielectric(c, eta[i]);
    if (!dispersive && !coated) {
      for (int k = 1; k < kLanes; ++k) eta[k] = eta[0], fresnel[k] = fresnel[0];
      break;
    }
  }
  out.pdf = 0;
  out.specular = true;
  const float fHero = fresnel[0];
  if (uLobe < fHero) {
    out.wi = reflect(s.wo, n);
    for (int i = 0; i < kLanes; ++i) out.weight[i] = s.rho[i] * fresnel[i] / fHero;
    out.terminateSecondary = false;
    out.eta = 1;
    return true;
  }
  Vec3 wt;
  if (!refract(s.wo, n, eta[0], wt)) return false; // unreachable: F = 1 under TIR
  out.wi = normalize(wt);
  out.eta = eta[0];
  out.terminateSecondary = dispersive;
  for (int i = 0; i < kLanes; ++i) {
    const float scale = s.mode == TransportMode::Radiance ? 1.0f / (eta[i] * eta[i]) : 1.0f;
    out.weight[i] = dispersive && i > 0 ? 0.0f : s.rho[i] * (1 - fresnel[i]) / (1 - fHero) * scale;
  }
  return true;
}

// A rough dielectric interface: GGX microfacets that reflect and refract (Walter, Marschner,
// Li & Torrance 2007, "Microfacet Models for Refraction through Rough Surfaces"), sampled
// through the normals visible from wo (Heitz 2018). Everything is computed with wo's side of
// the surface as +z; s.eta holds each lane's s.n(other side) / s.n(wo's side).
//
// Dispersion: a refracted direction belongs to one index. When the index varies over the lanes,
// a transmitted sample carries the hero alone (the integrator's heroOnly(), as for smooth
// glass), and so does the transmission part of f() used by next-event estimation (hero lane
// times kLanes, others 0): both techniques then estimate the hero's transmission with the
// hero's densities, and every wavelength is the hero equally often (a path that already carries
// the hero alone, setHeroAlone(), is not scaled again). Reflection keeps all lanes.
// The generalized half vector of a refraction from o (above) into i (below) with relative index
// eta, facing +z: h ~ o + eta i (Walter et al. 2007, eq. 16).
Vec3 refractionHalfVector(const Vec3& o, const Vec3& i, float eta) {
  const Vec3 h = normalize(o + i * eta);
  return h.z < 0 ? -h : h;
}

// wo and wi in the microfacet frame with wo's side as +z; false when there is no such pair:
// not a rough dielectric, wi in the surface, or the geometric normal disagreeing (reflection
// must stay on wo's side, transmission must cross).
bool roughPair(const BsdfState& s, const Vec3& wi, Vec3& o, Vec3& i) {
  if (!rough(s)) return false;
  const float side = dot(s.wo, s.n) > 0 ? 1.0f : -1.0f;
  o = s.frame.toLocal(s.wo) * side;
  i = s.frame.toLocal(wi) * side;
  if (o.z <= 0 || i.z == 0) return false;
  return ((dot(wi, s.ng) > 0) == (dot(s.wo, s.ng) > 0)) == (i.z > 0);
}

SampledSpectrum roughF(const BsdfState& s, const Vec3& wi) {
  Vec3 o, i;
  if (!roughPair(s, wi, o, i)) return {};
  SampledSpectrum f;
  if (i.z > 0) { // reflection: f |cos i| = D G2 F / (4 cos o)
    const Vec3 h = normalize(o + i);
    const float common = s.alpha.d(h) * s.alpha.g2(o, i) / (4 * o.z);
    for (int k = 0; k < kLanes; ++k) f[k] = common * fresnelDielectric(dot(o, h), s.eta[k]);
    return f * s.rho;
  }
  // transmission: f |cos i| = D G2 (1 - F) |i.h| |o.h| / (cos o (o.h + eta i.h)^2), times eta^2
  // for energy (radiance is divided by eta^2 on entering a denser medium)
  const bool dispersive = s.material->ior.dispersive();
  for (int k = 0; k < (dispersive ? 1 : kLanes); ++k) {
    const float eta = s.eta[k];
    const Vec3 h = refractionHalfVector(o, i, eta);
    const float oh = dot(o, h), ih = dot(i, h);
    if (oh <= 0 || ih >= 0) return {};
    const float denom = oh + eta * ih;
    float v = s.alpha.d(h) * s.alpha.g2(o, i) * (1 - fresnelDielectric(oh, eta)) * -ih * oh /
              (o.z * denom * denom);
    if (s.mode == TransportMode::Energy) v *= eta * eta;
    f[k] = v * s.rho[k];
  }
  // dispersive: the hero's alone, scaled by kLanes unless the path already carries the hero
  // alone (its weight holds that factor)
  if (!dispersive) return f;
  if (!s.heroAlone) return heroOnly(f);
  for (int k = 1; k < kLanes; ++k) f[k] = 0;
  return f;
}

float roughPdf(const BsdfState& s, const Vec3& wi) {
  Vec3 o, i;
  if (!roughPair(s, wi, o, i)) return 0;
  const float eta = s.eta[0];
  if (i.z > 0) {
    const Vec3 h = normalize(o + i);
    return s.alpha.visibleNormalPdf(o, h) / (4 * dot(o, h)) * fresnelDielectric(dot(o, h), eta);
  }
  const Vec3 h = refractionHalfVector(o, i, eta);
  const float oh = dot(o, h), ih = dot(i, h);
  if (oh <= 0 || ih >= 0) return 0;
  const float denom = ih + oh / eta; // dh / dwi = |i.h| / (i.h + o.h / eta)^2
  return s.alpha.visibleNormalPdf(o, h) * -ih / (denom * denom) * (1 - fresnelDielectric(oh, eta));
}

// A visible normal h from D_o; reflect with the hero's probability F(o.h), else refract
// through h with the hero's index. Weights: F_k / F_hero G2 / G1(o) after a reflection,
// (1 - F_k) / (1 - F_hero) G2 / G1(o) / eta^2 (radiance) after a refraction.
bool sampleRough(const BsdfState& s, float uLobe, Sample2 u, BsdfSample& out) {
  const float side = dot(s.wo, s.n) > 0 ? 1.0f : -1.0f;
  const Vec3 o = s.frame.toLocal(s.wo) * side;
  if (o.z <= 0) return false;
  const Vec3 h = s.alpha.sampleVisibleNormal(o, u);
  const float oh = dot(o, h);
  if (!(oh > 0)) return false;
  SampledSpectrum fresnel;
  for (int k = 0; k < kLanes; ++k) fresnel[k] = fresnelDielectric(oh, s.eta[k]);
  const float fHero = fresnel[0];
  const float pdfH = s.alpha.visibleNormalPdf(o, h);
  out.specular = false;
  if (uLobe < fHero) {
    const Vec3 i = h * (2 * oh) - o;
    if (i.z <= 0) return false;
    out.wi = s.frame.toWorld(i * side);
    if ((dot(out.wi, s.ng) > 0) != (dot(s.wo, s.ng) > 0)) return false;
    const float g = s.alpha.g2(o, i) / s.alpha.g1(o);
    for (int k = 0; k < kLanes; ++k) out.weight[k] = s.rho[k] * fresnel[k] / fHero * g;
    out.pdf = pdfH / (4 * oh) * fHero;
    out.terminateSecondary = false;
    out.eta = 1;
    return true;
  }
  const float eta = s.eta[0];
  Vec3 t;
  if (!refract(o, h, eta, t)) return false; // F = 1 under total internal reflection
  const Vec3 i = normalize(t);
  if (i.z >= 0) return false;
  out.wi = s.frame.toWorld(i * side);
  if ((dot(out.wi, s.ng) > 0) == (dot(s.wo, s.ng) > 0)) return false;
  const float ih = dot(i, h);
  const float denom = ih + oh / eta;
  out.pdf = pdfH * -ih / (denom * denom) * (1 - fHero);
  if (!(out.pdf > 0)) return false;
  const bool dispersive = s.material->ior.dispersive();
  const float g = s.alpha.g2(o, i) / s.alpha.g1(o);
  for (int k = 0; k < kLanes; ++k) {
    const float scale = s.mode == TransportMode::Radiance ? 1.0f / (s.eta[k] * s.eta[k]) : 1.0f;
    out.weight[k] =
        dispersive && k > 0 ? 0.0f : s.rho[k] * (1 - fresnel[k]) / (1 - fHero) * g * scale;
  }
  out.terminateSecondary = dispersive;
  out.eta = eta;
  return true;
}

} // namespace

template <>
uint8_t Dielectric::lobes(const Material& m) {
  return roughMicrofacets(m) ? kGlossyReflection | kGlossyTransmission
                             : kSpecularReflection | kSpecularTransmission;
}

// The outward normal stays (whether the path enters or leaves); a rough surface's microfacet
// frame and the lanes' relative index from wo's side.
template <>
void Dielectric::prepare(BsdfState& s) {
  const Material& m = *s.material;
  if (!roughMicrofacets(m)) return;
  s.alpha = clampedGgx(m);
  s.frame = Frame::fromNormal(s.n);
  const bool entering = dot(s.wo, s.n) > 0;
  for (int i = 0; i < kLanes; ++i) {
    const float ior = static_cast<float>(m.ior.at(s.lambda->lambda[i]));
    s.eta[i] = entering ? ior : 1.0f / ior;
  }
}

template <>
SampledSpectrum Dielectric::f(const BsdfState& s, const Vec3& wi) {
  return roughF(s, wi);
}

template <>
SampledSpectrum Dielectric::diffuseLobe(const BsdfState&, const Vec3&) {
  return {};
}

template <>
float Dielectric::pdf(const BsdfState& s, const Vec3& wi) {
  return roughPdf(s, wi);
}

template <>
bool Dielectric::sample(const BsdfState& s, float uLobe, Sample2 u, BsdfSample& out) {
  return rough(s) ? sampleRough(s, uLobe, u, out) : sampleSmooth(s, uLobe, out);
}

template <>
int Dielectric::specularLobes(const BsdfState& s, SpecularLobe (&out)[2]) {
  if (rough(s)) return 0;
  const Material& m = *s.material;
  const float c = dot(s.wo, s.n);
  // The Fresnel split: the reflected and (unless totally reflected) the refracted ray.
  const bool entering = c > 0;
  const Vec3 n = entering ? s.n : -s.n;
  SampledSpectrum fr, tr;
  float etaHero = 1;
  for (int i = 0; i < kLanes; ++i) {
    const float ior = static_cast<float>(m.ior.at(s.lambda->lambda[i]));
    const float eta = entering ? ior : 1.0f / ior;
    if (i == 0) etaHero = eta;
    fr[i] = dielectricReflectance(m, std::abs(c), entering ? 1.0f : ior, entering ? ior : 1.0f,
                                  s.lambda->lambda[i]);
    tr[i] = s.mode == TransportMode::Radiance ? (1 - fr[i]) / (eta * eta) : 1 - fr[i];
  }
  out[0] = {reflect(s.wo, n), s.rho * fr, false};
  Vec3 wt;
  if (!refract(s.wo, n, etaHero, wt)) return 1;
  out[1] = {normalize(wt), s.rho * tr, m.ior.dispersive()};
  return 2;
}

// rho is a transmission tint: every lobe is linear in it.
template <>
float Dielectric::reflectanceLogSlope(const BsdfState&, const Vec3&, float rho, bool, bool albedo,
                                      bool& zero) {
  return inverseReflectanceSlope(rho, albedo, zero);
}

template <>
bool Dielectric::roughnessLogSlopes(const BsdfState&, const Vec3&, float&, float&) {
  return false; // a rough dielectric's roughness is not differentiated
}

template <>
BsdfDerivativeSteps Dielectric::derivativeSteps(const Material& m) {
  BsdfDerivativeSteps steps = microfacetDerivativeSteps(m);
  if (!roughMicrofacets(m)) return steps; // smooth
  const float width = std::max(std::min(m.alphaU, m.alphaV), 1e-4f);
  // A rough dielectric's transmitted lobe is narrower in wo and wi by |eta - 1| / eta: the
  // half vector -(wo + eta wi) turns eta / |eta - 1| times faster than wi near the straight
  // direction (Walter et al. 2007, eq. 16); turning the normal turns it at the normal's rate.
  float narrowing = 1;
  for (const float nm : {300.0f, 550.0f, 1100.0f}) {
    const float eta = static_cast<float>(m.ior.at(nm));
    narrowing = std::min(narrowing, std::abs(eta - 1) / std::max(eta, 1.0f));
  }
  narrowing = std::max(narrowing, 1e-3f);
  steps.directions = std::min(1e-3f, width * narrowing / 8);
  // The cancellation in wo + eta wi amplifies the evaluation's rounding by 1 / narrowing:
  // the normals' step grows as much (within the lobe's eighth) to keep its noise.
  steps.normals = std::min(1e-3f / narrowing, width / 8);
  return steps;
}

template <>
SampledSpectrum Dielectric::straightTransmittance(const Material&, const SampledWavelengths&,
                                                  float) {
  return {};
}

template <>
bool Dielectric::albedoIsReflectance(const Material&) {
  return false;
}

template <>
bool Dielectric::roughnessDifferentiable(const Material&) {
  return false;
}

} // namespace nx

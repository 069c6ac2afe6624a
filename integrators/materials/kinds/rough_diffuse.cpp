// A rough diffuse surface (possibly fluorescent): paper, card, plaster, a matte target, which
// reflect back towards the light more than a Lambertian surface and darken less at grazing
// view. Fujii's improved Oren-Nayar lobe (Fujii 2012, "A tiny improvement of Oren-Nayar
// reflectance model") for single scattering, with the energy it loses between facets put back
// by the multiple-scattering lobe of EON (Portsmouth, Kutz and Hill 2025, "EON: A practical
// energy-preserving rough diffuse BRDF", JCGT 14(1)):
//   f_ss = rho / pi (A + B s / t),  s = wi . wo - cos_i cos_o,  t = max(cos_i, cos_o) if s > 0
//          else 1,  A = 1 / (1 + (pi/2 - 2/3) sigma),  B = sigma A;
//   f_ms = rho_ms / pi (1 - E(cos_o)) (1 - E(cos_i)) / (1 - E_avg),
//          rho_ms = rho^2 E_avg / (1 - rho (1 - E_avg)),
// E(mu) the directional albedo of f_ss at rho = 1 and E_avg its cosine-weighted mean. At
// rho = 1 the albedo is 1 from every direction; f is reciprocal. E(mu) is computed here by
// quadrature when the material is built (not the paper's fitted approximation) and tabulated.
// A fluorescent base re-radiates with the lobe of rho = 1 (f_ss + f_ms, albedo 1) scaled by
// its re-radiation albedo. Its parameters, build and scattering model (below).

#include <cmath>
#include <map>
#include <memory>
#include <mutex>

#include "integrators/materials/kinds/rough_diffuse.h"
#include "integrators/materials/material_kind.h"
#include "integrators/materials/scattering_model.h"
#include "integrators/sampling.h"

namespace nx {
namespace {

// Fujii's s / t for unit wi, wo with cosines ci, co to the normal (the lobe's angular term).
double fujiiTerm(double s, double ci, double co) {
  return s > 0 ? s / std::max(ci, co) : s;
}

// E(mu) = integral of (A + B s / t) cos_i / pi over the hemisphere, for cos_o = mu: midpoint
// quadrature in theta_i and phi (the integrand is even in phi), 384 x 384 points.
double singleScatterAlbedo(double mu, double a, double b) {
  constexpr int kTheta = 384, kPhi = 384;
  const double so = std::sqrt(std::max(0.0, 1 - mu * mu));
  double sum = 0;
  for (int i = 0; i < kTheta; ++i) {
    const double theta = (i + 0.5) * (kPi / 2) / kTheta;
    const double ci = std::cos(theta), si = std::sin(theta);
    double ring = 0;
    for (int j = 0; j < kPhi; ++j) {
      const double phi = (j + 0.5) * kPi / kPhi;
      ring += a + b * fujiiTerm(si * so * std::cos(phi), ci, mu);
    }
    sum += ring * (kPi / kPhi) * 2 * ci * si;
  }
  return sum * (kPi / 2) / kTheta / kPi;
}

RoughDiffuseLobe roughDiffuseLobe(double sigma) {
  RoughDiffuseLobe lobe;
  const double a = 1 / (1 + (kPi / 2 - 2.0 / 3.0) * sigma), b = sigma * a;
  lobe.a = static_cast<float>(a);
  lobe.b = static_cast<float>(b);
  for (int k = 0; k < RoughDiffuseLobe::kNodes; ++k)
    lobe.albedo[static_cast<size_t>(k)] = static_cast<float>(
        singleScatterAlbedo(static_cast<double>(k) / (RoughDiffuseLobe::kNodes - 1), a, b));
  // E_avg = 2 integral_0^1 E(mu) mu dmu, by the interpolant on a fine grid.
  double mean = 0;
  constexpr int kSteps = 4096;
  for (int k = 0; k < kSteps; ++k) {
    const double mu = (k + 0.5) / kSteps;
    mean += 2 * roughDiffuseAlbedo(lobe, static_cast<float>(mu)) * mu / kSteps;
  }
  lobe.meanAlbedo = static_cast<float>(std::min(mean, 1.0));
  return lobe;
}

// The lobe of roughness sigma, shared by every material of that sigma (built once: its
// quadrature takes milliseconds; equal constants are then the same pointer, as Material asks).
std::shared_ptr<const RoughDiffuseLobe> sharedLobe(double sigma) {
  static std::mutex mutex;
  static std::map<double, std::weak_ptr<const RoughDiffuseLobe>> lobes;
  const std::lock_guard lock(mutex);
  std::erase_if(lobes, [](const auto& entry) { return entry.second.expired(); });
  std::weak_ptr<const RoughDiffuseLobe>& slot = lobes[sigma];
  if (std::shared_ptr<const RoughDiffuseLobe> lobe = slot.lock()) return lobe;
  auto lobe = std::make_shared<const RoughDiffuseLobe>(roughDiffuseLobe(sigma));
  slot = lobe;
  return lobe;
}

Material buildRoughDiffuse(const MaterialKindSpec& kind, const ParameterSet& p,
                           const MaterialInputs& in) {
  Material m;
  m.kind = MaterialKind::RoughDiffuse;
  const double sigma = p.number("sigma").value_or(kind.numberDefault("sigma"));
  m.modelConstants = sharedLobe(sigma);
  setSurfaceReflectance(m, p, in, false, "reflectance");
  setFluorescence(m, p, in);
  return m;
}

constexpr KindParameter kParams[] = {{"color", "", ""},
                                     {"reflectance", "", "albedo rho (required unless it emits)"},
                                     {"sigma", "0.5", ""},
                                     {"fluorescence", "", "of the rough diffuse lobe"}};

constexpr std::pair<const char*, const char*> kRefusals[] = {
    {"roughness", "<roughness> weighs the mirror mixture's Lambertian lobe; here <sigma> is the "
                  "surface's roughness"},
    {"alpha", "GGX roughness is for conductors and dielectrics; here <sigma> is the roughness"},
    {"ior", "an index of refraction is for dielectrics and coated"},
    {"coating", "thin films lie on conductors and smooth dielectrics"}};

constexpr const char* kExamples[] = {"<sigma>1</sigma><reflectance>1</reflectance>",
                                     "<sigma>0.05</sigma><reflectance>0.4</reflectance>",
                                     "<sigma>0</sigma><reflectance>1</reflectance>"};

} // namespace

extern const MaterialKindSpec kRoughMatteKind{
    "rough_matte",
    "rough diffuse (Oren-Nayar as improved by Fujii, energy kept by EON's multiple scattering)",
    kParams,
    kRefusals,
    buildRoughDiffuse,
    kExamples};

float roughDiffuseAlbedo(const RoughDiffuseLobe& lobe, float mu) {
  constexpr int n = RoughDiffuseLobe::kNodes;
  const float x = std::clamp(mu, 0.0f, 1.0f) * (n - 1);
  const int k = std::min(static_cast<int>(x), n - 2);
  const float t = x - static_cast<float>(k);
  auto at = [&](int j) { return lobe.albedo[static_cast<size_t>(std::clamp(j, 0, n - 1))]; };
  // Catmull-Rom through the nodes (C1: the lobe's derivatives stay continuous); the ends
  // extrapolate linearly.
  const float p0 = k > 0 ? at(k - 1) : 2 * at(0) - at(1), p1 = at(k), p2 = at(k + 1),
              p3 = k + 2 < n ? at(k + 2) : 2 * at(n - 1) - at(n - 2);
  const float t2 = t * t, t3 = t2 * t;
  return 0.5f * (2 * p1 + (p2 - p0) * t + (2 * p0 - 5 * p1 + 4 * p2 - p3) * t2 +
                 (3 * p1 - p0 - 3 * p2 + p3) * t3);
}

// ---- the scattering model (ScatteringModel<RoughDiffuse>) ----

const RoughDiffuseLobe& roughDiffuseLobeOf(const Material& m) {
  return m.modelConstantsAs<RoughDiffuseLobe>();
}

using RoughDiffuse = ScatteringModel<MaterialKind::RoughDiffuse>;

namespace {

// The lobe's factors at one pair of directions: the single-scattering term A + B s / t, the
// multiple-scattering term (1 - E_o)(1 - E_i) / (1 - E_avg) and cos_i (all 0 below the surface).
struct Shape {
  float single = 0, multiple = 0, cosine = 0;
};

Shape shapeAt(const BsdfState& s, const Vec3& wi) {
  const RoughDiffuseLobe& lobe = roughDiffuseLobeOf(*s.material);
  const float ci = dot(wi, s.n), co = dot(s.wo, s.n);
  if (ci <= 0 || co <= 0 || dot(wi, s.ng) <= 0) return {};
  const float sTerm = dot(wi, s.wo) - ci * co;
  const float single = lobe.a + lobe.b * static_cast<float>(fujiiTerm(sTerm, ci, co));
  const float lost = 1 - lobe.meanAlbedo;
  const float multiple =
      lost > 1e-6f ? (1 - roughDiffuseAlbedo(lobe, co)) * (1 - roughDiffuseAlbedo(lobe, ci)) / lost
                   : 0.0f;
  return {std::max(single, 0.0f), std::max(multiple, 0.0f), ci};
}

} // namespace

float roughDiffuseMultipleAlbedo(const RoughDiffuseLobe& lobe, float rho) {
  const float e = lobe.meanAlbedo;
  const float d = 1 - rho * (1 - e);
  return d > 0 ? rho * rho * e / d : 0.0f;
}

template <>
SampledSpectrum RoughDiffuse::f(const BsdfState& s, const Vec3& wi) {
  const Shape g = shapeAt(s, wi);
  if (!(g.cosine > 0)) return {};
  SampledSpectrum f;
  const float c = g.cosine * static_cast<float>(kInvPi);
  for (int i = 0; i < kLanes; ++i)
    f[i] = (s.rho[i] * g.single +
            roughDiffuseMultipleAlbedo(roughDiffuseLobeOf(*s.material), s.rho[i]) * g.multiple) *
           c;
  return f;
}

// Its own slope: rho_ms is not linear in rho.
template <>
float RoughDiffuse::reflectanceLogSlope(const BsdfState& s, const Vec3& wi, float rho, bool,
                                        bool albedo, bool& zero) {
  zero = false;
  if (!albedo) return 0.0f;
  if (!(rho > 0)) {
    zero = true;
    return 0.0f;
  }
  const Shape g = shapeAt(s, wi);
  const float e = roughDiffuseLobeOf(*s.material).meanAlbedo, d = 1 - rho * (1 - e);
  if (!(g.cosine > 0) || !(d > 0)) return 0;
  // d rho_ms / d rho = E_avg rho (2 - rho (1 - E_avg)) / (1 - rho (1 - E_avg))^2
  const float slope = e * rho * (2 - rho * (1 - e)) / (d * d);
  const float value = rho * g.single +
                      roughDiffuseMultipleAlbedo(roughDiffuseLobeOf(*s.material), rho) * g.multiple;
  return value > 0 ? (g.single + slope * g.multiple) / value : 0.0f;
}

// Cosine-weighted directions: the weight f |cos| / pdf = rho (A + B s / t) + rho_ms g_ms per lane.
template <>
bool RoughDiffuse::sample(const BsdfState& s, float, Sample2 u, BsdfSample& out) {
  if (dot(s.wo, s.n) <= 0) return false;
  const Frame frame = Frame::fromNormal(s.n);
  const Vec3 local = sampleCosineHemisphere(u);
  if (local.z <= 0) return false;
  out.wi = frame.toWorld(local);
  const Shape g = shapeAt(s, out.wi);
  if (!(g.cosine > 0)) return false;
  out.pdf = cosineHemispherePdf(local.z);
  out.specular = false;
  out.terminateSecondary = false;
  out.eta = 1;
  out.diffuseScale = SampledSpectrum::filled(g.single + g.multiple);
  for (int i = 0; i < kLanes; ++i)
    out.weight[i] =
        s.rho[i] * g.single +
        roughDiffuseMultipleAlbedo(roughDiffuseLobeOf(*s.material), s.rho[i]) * g.multiple;
  return true;
}

template <>
uint8_t RoughDiffuse::lobes(const Material&) {
  return kDiffuseReflection;
}

template <>
void RoughDiffuse::prepare(BsdfState& s) {
  s.faceWo();
}

// The lobe of rho = 1 (albedo 1).
template <>
SampledSpectrum RoughDiffuse::diffuseLobe(const BsdfState& s, const Vec3& wi) {
  const Shape g = shapeAt(s, wi);
  return SampledSpectrum::filled((g.single + g.multiple) * g.cosine * static_cast<float>(kInvPi));
}

template <>
float RoughDiffuse::pdf(const BsdfState& s, const Vec3& wi) {
  return dot(s.wo, s.n) > 0 ? cosineHemispherePdf(dot(wi, s.n)) : 0.0f;
}

template <>
int RoughDiffuse::specularLobes(const BsdfState&, SpecularLobe (&)[2]) {
  return 0;
}

template <>
bool RoughDiffuse::roughnessLogSlopes(const BsdfState&, const Vec3&, float&, float&) {
  return false; // sigma is not differentiated
}

template <>
BsdfDerivativeSteps RoughDiffuse::derivativeSteps(const Material&) {
  return {};
}

template <>
SampledSpectrum RoughDiffuse::straightTransmittance(const Material&, const SampledWavelengths&,
                                                    float) {
  return {};
}

template <>
bool RoughDiffuse::albedoIsReflectance(const Material&) {
  return false;
}

template <>
bool RoughDiffuse::roughnessDifferentiable(const Material&) {
  return false;
}

} // namespace nx

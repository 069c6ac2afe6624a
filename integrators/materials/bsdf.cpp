#include "integrators/materials/bsdf.h"

#include <cmath>

#include "integrators/materials/fresnel.h"
#include "integrators/sampling.h"

namespace nx {

SurfaceBsdf::SurfaceBsdf(const Material& m, const SampledWavelengths& lambda,
                         const SampledSpectrum& rho, const Vec3& ng, const Vec3& ns, const Vec3& wo,
                         TransportMode mode)
    : material_(&m), lambda_(&lambda), rho_(rho), wo_(wo), mode_(mode) {
  // Opaque surfaces scatter on the side they are seen from (decided by the geometric normal);
  // dielectrics keep the outward normal to know whether the path enters or leaves.
  const bool opaque = m.kind == MaterialKind::Mixture || m.kind == MaterialKind::Conductor ||
                      m.kind == MaterialKind::CoatedDiffuse || m.kind == MaterialKind::RoughDiffuse;
  const bool flip = opaque && dot(wo, ng) < 0;
  ng_ = flip ? -ng : ng;
  n_ = flip ? -ns : ns;
  if (m.kind == MaterialKind::Conductor) {
    m.conductorEta.evaluate(lambda, eta_);
    m.conductorK.evaluate(lambda, k_);
    // Rougher than 1e-4 is a microfacet surface (clamped there), else a smooth one.
    if (std::max(m.alphaU, m.alphaV) >= 1e-4f)
      alpha_ = {std::max(m.alphaU, 1e-4f), std::max(m.alphaV, 1e-4f)};
    frame_ = Frame::fromNormal(n_);
  }
  if (m.kind == MaterialKind::Dielectric && std::max(m.alphaU, m.alphaV) >= 1e-4f) {
    alpha_ = {std::max(m.alphaU, 1e-4f), std::max(m.alphaV, 1e-4f)};
    frame_ = Frame::fromNormal(n_);
    const bool entering = dot(wo, n_) > 0;
    for (int i = 0; i < kLanes; ++i) {
      const float ior = static_cast<float>(m.ior.at(lambda.lambda[i]));
      eta_[i] = entering ? ior : 1.0f / ior;
    }
  }
}

BsdfDerivativeSteps bsdfDerivativeSteps(const Material& m) {
  const bool microfacet = m.kind == MaterialKind::Conductor || m.kind == MaterialKind::Dielectric;
  if (!microfacet || std::max(m.alphaU, m.alphaV) < 1e-4f) return {}; // the constructor's clamp
  const float width = std::max(std::min(m.alphaU, m.alphaV), 1e-4f);
  BsdfDerivativeSteps steps{std::min(1e-3f, width / 8), std::min(1e-3f, width / 8)};
  // A rough dielectric's transmitted lobe is narrower in wo and wi by |eta - 1| / eta: the
  // half vector -(wo + eta wi) turns eta / |eta - 1| times faster than wi near the straight
  // direction (Walter et al. 2007, eq. 16); turning the normal turns it at the normal's rate.
  if (m.kind == MaterialKind::Dielectric) {
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
  }
  return steps;
}

void SurfaceBsdf::orient(const Vec3& dpdu) {
  if (alpha_.ax == alpha_.ay) return; // isotropic (or smooth, or not a microfacet surface)
  const Vec3 t = dpdu - n_ * dot(dpdu, n_);
  const float len = length(t);
  if (!(len > 1e-12f) || !std::isfinite(len)) return;
  frame_.s = t * (1.0f / len);
  frame_.t = cross(n_, frame_.s);
}

uint8_t SurfaceBsdf::lobes() const {
  if (material_->kind == MaterialKind::Interface) return kSpecularTransmission;
  if (material_->kind == MaterialKind::Conductor)
    return smoothConductor() ? kSpecularReflection : kGlossyReflection;
  if (material_->kind == MaterialKind::CoatedDiffuse)
    return kSpecularReflection | kDiffuseReflection;
  if (material_->kind == MaterialKind::RoughDiffuse) return kDiffuseReflection;
  if (material_->kind == MaterialKind::ThinDielectric)
    return kSpecularReflection | kSpecularTransmission;
  if (material_->kind == MaterialKind::Dielectric)
    return roughDielectric() ? kGlossyReflection | kGlossyTransmission
                             : kSpecularReflection | kSpecularTransmission;
  const float r = material_->roughness;
  return static_cast<uint8_t>((r > 0 ? kDiffuseReflection : 0) | (r < 1 ? kSpecularReflection : 0));
}

float SurfaceBsdf::diffuseFactor(const Vec3& wi) const {
  if (material_->kind != MaterialKind::Mixture || !(material_->roughness > 0)) return 0;
  const float c = dot(wi, n_);
  if (c <= 0 || dot(wo_, n_) <= 0 || dot(wi, ng_) <= 0) return 0;
  return material_->roughness * static_cast<float>(kInvPi) * c;
}

SampledSpectrum SurfaceBsdf::diffuseLobe(const Vec3& wi) const {
  if (material_->kind == MaterialKind::RoughDiffuse) { // the lobe of rho = 1 (albedo 1)
    const RoughDiffuseShape g = roughDiffuseShape(wi);
    return SampledSpectrum::filled((g.single + g.multiple) * g.cosine * static_cast<float>(kInvPi));
  }
  if (material_->kind != MaterialKind::CoatedDiffuse)
    return SampledSpectrum::filled(diffuseFactor(wi));
  const float ci = dot(wi, n_), co = dot(wo_, n_);
  if (ci <= 0 || co <= 0 || dot(wi, ng_) <= 0) return {};
  // (1 - F(i)) (1 - F(o)) |cos i| / (pi n^2 (1 - rho Fi)): transmitted in, scattered by the
  // base, reflected between base and coat (Fi the coat's internal diffuse reflectance), out.
  const float n = static_cast<float>(material_->ior.at(lambda_->lambda[0]));
  const float t = (1 - coatReflectance(ci)) * (1 - coatReflectance(co)) * ci *
                  static_cast<float>(kInvPi) / (n * n);
  SampledSpectrum f;
  for (int i = 0; i < kLanes; ++i) f[i] = t / (1 - rho_[i] * material_->coatInternalReflectance);
  return f;
}

float SurfaceBsdf::pdf(const Vec3& wi) const {
  if (material_->kind == MaterialKind::Dielectric) return roughDielectricPdf(wi);
  if (material_->kind == MaterialKind::RoughDiffuse)
    return dot(wo_, n_) > 0 ? cosineHemispherePdf(dot(wi, n_)) : 0.0f;
  if (material_->kind == MaterialKind::CoatedDiffuse) {
    const float co = dot(wo_, n_);
    if (co <= 0) return 0;
    return (1 - coatReflectance(co)) * cosineHemispherePdf(dot(wi, n_));
  }
  if (material_->kind == MaterialKind::Conductor) {
    if (smoothConductor() || dot(wi, ng_) <= 0) return 0;
    const Vec3 o = frame_.toLocal(wo_), i = frame_.toLocal(wi);
    if (o.z <= 0 || i.z <= 0) return 0;
    const Vec3 h = normalize(o + i);
    return alpha_.g1(o) * alpha_.d(h) / (4 * o.z);
  }
  if (material_->kind != MaterialKind::Mixture || !(material_->roughness > 0) || dot(wo_, n_) <= 0)
    return 0;
  return material_->roughness * cosineHemispherePdf(dot(wi, n_));
}

bool SurfaceBsdf::sample(float uLobe, Sample2 u, BsdfSample& out) const {
  switch (material_->kind) {
  case MaterialKind::Mixture:
    return sampleMixture(uLobe, u, out);
  case MaterialKind::Dielectric:
    return roughDielectric() ? sampleRoughDielectric(uLobe, u, out) : sampleDielectric(uLobe, out);
  case MaterialKind::Interface:
    // Index-matched: the path continues straight on, every lane unchanged.
    out.wi = -wo_;
    out.weight = SampledSpectrum::filled(1.0f);
    out.pdf = 0;
    out.specular = true;
    out.terminateSecondary = false;
    out.eta = 1;
    out.straight = true;
    return true;
  case MaterialKind::ThinDielectric:
    return sampleThinDielectric(uLobe, out);
  case MaterialKind::Conductor:
    return sampleConductor(u, out);
  case MaterialKind::CoatedDiffuse:
    return sampleCoatedDiffuse(uLobe, u, out);
  case MaterialKind::RoughDiffuse:
    return sampleRoughDiffuse(u, out);
  }
  return false;
}

int SurfaceBsdf::specularLobes(SpecularLobe (&out)[2]) const {
  const Material& m = *material_;
  const float c = dot(wo_, n_);
  switch (m.kind) {
  case MaterialKind::Mixture:
    if (!(m.roughness < 1) || c <= 0) return 0;
    out[0] = {reflect(wo_, n_), rho_ * (1 - m.roughness), false};
    return 1;
  case MaterialKind::Conductor: {
    BsdfSample bs;
    if (!smoothConductor() || !sampleConductor({}, bs)) return 0;
    out[0] = {bs.wi, bs.weight, false};
    return 1;
  }
  case MaterialKind::CoatedDiffuse:
    if (c <= 0) return 0;
    out[0] = {reflect(wo_, n_), SampledSpectrum::filled(coatReflectance(c)), false};
    return 1;
  case MaterialKind::Interface:
    out[0] = {-wo_, SampledSpectrum::filled(1.0f), false};
    return 1;
  case MaterialKind::RoughDiffuse:
    return 0;
  case MaterialKind::ThinDielectric: {
    const float ac = std::abs(c);
    SampledSpectrum r, t;
    for (int i = 0; i < kLanes; ++i) {
      r[i] = thinSlabReflectance(ac, static_cast<float>(m.ior.at(lambda_->lambda[i])));
      t[i] = 1 - r[i];
    }
    out[0] = {reflect(wo_, c > 0 ? n_ : -n_), rho_ * r, false};
    out[1] = {-wo_, rho_ * t, false};
    return 2;
  }
  case MaterialKind::Dielectric: {
    if (roughDielectric()) return 0;
    // The Fresnel split: the reflected and (unless totally reflected) the refracted ray.
    const bool entering = c > 0;
    const Vec3 n = entering ? n_ : -n_;
    SampledSpectrum fr, tr;
    float etaHero = 1;
    for (int i = 0; i < kLanes; ++i) {
      const float ior = static_cast<float>(m.ior.at(lambda_->lambda[i]));
      const float eta = entering ? ior : 1.0f / ior;
      if (i == 0) etaHero = eta;
      fr[i] = dielectricReflectance(m, std::abs(c), entering ? 1.0f : ior, entering ? ior : 1.0f,
                                    lambda_->lambda[i]);
      tr[i] = mode_ == TransportMode::Radiance ? (1 - fr[i]) / (eta * eta) : 1 - fr[i];
    }
    out[0] = {reflect(wo_, n), rho_ * fr, false};
    Vec3 wt;
    if (!refract(wo_, n, etaHero, wt)) return 1;
    out[1] = {normalize(wt), rho_ * tr, m.ior.dispersive()};
    return 2;
  }
  }
  return 0;
}

// Mixture and dielectrics (rho a tint): 1/rho; coated diffuse: its diffuse lobe
// rho t / (1 - rho F_i) gives 1/rho + F_i / (1 - rho F_i), its coat reflection nothing; rough
// diffuse: its own (rho_ms is not linear in rho); conductors and interfaces do not use rho.
float SurfaceBsdf::reflectanceLogSlope(const Vec3& wi, float rho, bool specular, bool albedo,
                                       bool& zero) const {
  zero = false;
  auto inverse = [&] {
    if (!albedo) return 0.0f;
    if (rho > 0) return 1.0f / rho;
    zero = true;
    return 0.0f;
  };
  const Material& m = *material_;
  switch (m.kind) {
  case MaterialKind::Mixture:
  case MaterialKind::Dielectric:
  case MaterialKind::ThinDielectric:
    return inverse();
  case MaterialKind::CoatedDiffuse: {
    if (specular) return 0.0f;
    const float fi = m.coatInternalReflectance;
    return inverse() + fi / (1 - rho * fi);
  }
  case MaterialKind::RoughDiffuse:
    if (!albedo) return 0.0f;
    if (!(rho > 0)) {
      zero = true;
      return 0.0f;
    }
    return roughDiffuseLogSlope(wi, rho);
  case MaterialKind::Conductor: // its reflectance is its complex index's
  case MaterialKind::Interface: // light passes unchanged
    return 0.0f;
  }
  return 0.0f; // not reached: every kind is a case (-Werror=switch)
}

} // namespace nx

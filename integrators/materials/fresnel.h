#pragma once
// Fresnel reflectance of smooth dielectric and conductor interfaces, and the refraction
// direction.

#include <algorithm>
#include <cmath>
#include <complex>

#include "core/math_util.h"
#include "core/vec3.h"

namespace nx {

/// Unpolarised Fresnel reflectance for light arriving with cosine cosI (> 0) at an interface
/// with relative index eta = n_transmitted / n_incident; 1 under total internal reflection.
/// The exact formula (average of the s and p reflectances), not Schlick's approximation.
inline float fresnelDielectric(float cosI, float eta) {
  cosI = std::clamp(cosI, 0.0f, 1.0f);
  const float sin2T = (1 - cosI * cosI) / (eta * eta);
  if (sin2T >= 1) return 1.0f;
  const float cosT = std::sqrt(1 - sin2T);
  const float rs = (cosI - eta * cosT) / (cosI + eta * cosT);
  const float rp = (eta * cosI - cosT) / (eta * cosI + cosT);
  return 0.5f * (rs * rs + rp * rp);
}

/// Unpolarised Fresnel reflectance of a conductor with complex index eta + i k (relative to
/// the outside medium) for light arriving with cosine cosI: the exact average of |r_s|^2 and
/// |r_p|^2 with the complex cosine of the transmitted angle, cos_t = sqrt(1 - sin^2 / n^2)
/// (Born & Wolf, sec. 14.2). k = 0 gives fresnelDielectric for eta >= 1.
inline float fresnelConductor(float cosI, float eta, float k) {
  using C = std::complex<float>;
  cosI = std::clamp(cosI, 0.0f, 1.0f);
  if (!(cosI > 0)) return 1.0f; // grazing (the formula's 0 / 0 for eta = 1, k = 0)
  const C n(eta, k);
  const C cosT = std::sqrt(C(1.0f) - (1 - cosI * cosI) / (n * n));
  const C rs = (cosI - n * cosT) / (cosI + n * cosT);
  const C rp = (n * cosI - cosT) / (n * cosI + cosT);
  return 0.5f * (std::norm(rs) + std::norm(rp));
}

/// Unpolarised reflectance of a thin film (thickness d_nm, real index n1) between an incident
/// medium of real index n0 and a substrate of complex index n2 = eta2 + i k2, for light of
/// wavelength lambda_nm arriving with cosine cos0: Airy's sum of the multiply reflected waves,
/// r = (r01 + r12 e^{i delta}) / (1 + r01 r12 e^{i delta}), delta = (4 pi / lambda) d q1, per
/// polarisation, with q_j = n_j cos(theta_j) = sqrt(n_j^2 - n0^2 sin^2(theta_0)) (principal root:
/// evanescent and absorbed waves decay), r_s = (q_i - q_j) / (q_i + q_j) and
/// r_p = (n_j^2 q_i - n_i^2 q_j) / (n_j^2 q_i + n_i^2 q_j) (Born & Wolf, sec. 1.6.4 and 14.4).
/// d_nm = 0 gives the substrate's Fresnel reflectance.
inline float thinFilmReflectance(float cos0, float n0, float n1, float eta2, float k2, float dNm,
                                 float lambdaNm) {
  using C = std::complex<double>;
  const double c = std::clamp(static_cast<double>(cos0), 0.0, 1.0);
  if (!(c > 0)) return 1.0f;
  const double s2 = static_cast<double>(n0) * n0 * (1 - c * c); // (n0 sin theta_0)^2
  const C e0(static_cast<double>(n0) * n0), e1(static_cast<double>(n1) * n1),
      e2 = C(eta2, k2) * C(eta2, k2); // n_j^2
  const C q0(n0 * c), q1 = std::sqrt(e1 - s2), q2 = std::sqrt(e2 - s2);
  const C phase = std::exp(C(0, 4 * kPi * dNm / lambdaNm) * q1);
  auto airy = [&](const C& r01, const C& r12) {
    return std::norm((r01 + r12 * phase) / (1.0 + r01 * r12 * phase));
  };
  const double rs = airy((q0 - q1) / (q0 + q1), (q1 - q2) / (q1 + q2));
  const double rp =
      airy((e1 * q0 - e0 * q1) / (e1 * q0 + e0 * q1), (e2 * q1 - e1 * q2) / (e2 * q1 + e1 * q2));
  return static_cast<float>(std::min(1.0, 0.5 * (rs + rp)));
}

/// Reflectance of a thin slab with parallel faces (a glass wall) for light arriving with
/// cosine cosI, its internal reflections summed: R = F + (1 - F)^2 F / (1 - F^2) = 2F / (1 + F)
/// with F the single-interface reflectance (absorption in the wall neglected).
inline float thinSlabReflectance(float cosI, float eta) {
  const float f = fresnelDielectric(cosI, eta);
  return f < 1 ? 2 * f / (1 + f) : 1.0f;
}

/// Refracts wi (pointing away from the surface, on the side of n, dot(wi, n) > 0) through an
/// interface with relative index eta = n_transmitted / n_incident. Returns false under total
/// internal reflection. Snell: sin(theta_t) = sin(theta_i) / eta.
inline bool refract(const Vec3& wi, const Vec3& n, float eta, Vec3& wt) {
  const float cosI = dot(n, wi);
  const float sin2T = std::max(0.0f, 1 - cosI * cosI) / (eta * eta);
  if (sin2T >= 1) return false;
  const float cosT = std::sqrt(1 - sin2T);
  wt = -wi / eta + n * (cosI / eta - cosT);
  return true;
}

/// Mirror reflection of wo about n.
inline Vec3 reflect(const Vec3& wo, const Vec3& n) {
  return n * (2 * dot(wo, n)) - wo;
}

} // namespace nx

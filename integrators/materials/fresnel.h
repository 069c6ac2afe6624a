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
/// |r_p|^2 (Born & Wolf, sec. 14.2), in real arithmetic. With s = sin(theta_i), the complex
/// n cos_t = a + i b has a^2 + b^2 = sqrt((eta^2 - k^2 - s^2)^2 + 4 eta^2 k^2) and
/// a^2 = ((a^2 + b^2) + (eta^2 - k^2 - s^2)) / 2, whence
/// R_s = (a^2 + b^2 - 2 a cos + cos^2) / (a^2 + b^2 + 2 a cos + cos^2) and
/// R_p = R_s ((a^2 + b^2) cos^2 - 2 a cos s^2 + s^4) / ((a^2 + b^2) cos^2 + 2 a cos s^2 + s^4).
/// k = 0 gives fresnelDielectric for eta >= 1. (The complex form through std::complex called
/// the C library's checked complex division and square root: a third of a rough-gold
/// scene's time.)
inline float fresnelConductor(float cosI, float eta, float k) {
  cosI = std::clamp(cosI, 0.0f, 1.0f);
  if (!(cosI > 0)) return 1.0f; // grazing (the formula's 0 / 0 for eta = 1, k = 0)
  const float cos2 = cosI * cosI, sin2 = 1 - cos2;
  const float t0 = eta * eta - k * k - sin2, cross = 2 * eta * k;
  const float modulus2 = std::sqrt(t0 * t0 + cross * cross); // a^2 + b^2
  // a^2 without cancellation where t0 < 0: (modulus2 + t0) = cross^2 / (modulus2 - t0).
  const float a2 = t0 >= 0 ? 0.5f * (modulus2 + t0)
                           : (modulus2 - t0 > 0 ? 0.5f * cross * cross / (modulus2 - t0) : 0.0f);
  const float twoACos = 2 * std::sqrt(a2) * cosI;
  const float rs = (modulus2 - twoACos + cos2) / (modulus2 + twoACos + cos2);
  const float sA = modulus2 * cos2 + sin2 * sin2, sB = twoACos * sin2;
  const float rp = rs * (sA - sB) / (sA + sB);
  return std::clamp(0.5f * (rs + rp), 0.0f, 1.0f);
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

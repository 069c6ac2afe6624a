#include <gtest/gtest.h>

#include "integrators/materials/bsdf.h"
#include "integrators/materials/fresnel.h"
#include "integrators/sampling.h"
#include "support/statistics.h"

namespace nx {
namespace {

Sample2 uniform2(uint32_t i, uint32_t d) {
  return samplePair(SamplerKind::Independent, i, 0, d, 5);
}

SampledWavelengths someWavelengths() {
  SampledWavelengths w;
  for (int i = 0; i < kLanes; ++i) {
    w.lambda[i] = 420.0f + 70.0f * static_cast<float>(i);
    w.pdf[i] = 1.0f / 300.0f;
  }
  return w;
}

Vec3 direction(float cosTheta, float phi) {
  const float s = std::sqrt(std::max(0.0f, 1 - cosTheta * cosTheta));
  return {s * std::cos(phi), s * std::sin(phi), cosTheta};
}

Material mixture(float r) {
  Material m;
  m.kind = MaterialKind::Mixture;
  m.roughness = r;
  return m;
}

Material dielectric(IorModel ior) {
  Material m;
  m.kind = MaterialKind::Dielectric;
  m.ior = ior;
  return m;
}

// The continuous lobe of the mixture is sampled with exactly its pdf (chi-square over the
// hemisphere), the mirror lobe with probability 1 - r, and every sample weighs rho.
TEST(Bsdf, MixtureSamplingMatchesPdf) {
  const SampledWavelengths lambda = someWavelengths();
  SampledSpectrum rho;
  for (int i = 0; i < kLanes; ++i) rho[i] = 0.2f + 0.2f * static_cast<float>(i);
  for (float r : {1.0f, 0.7f, 0.3f}) {
    const Material m = mixture(r);
    const Vec3 ng(0, 0, 1), wo = normalize(Vec3(0.3f, -0.2f, 0.8f));
    const SurfaceBsdf bsdf(m, lambda, rho, ng, wo);
    const int n = 200000, nz = 20, nphi = 40;
    std::vector<double> obs(nz * nphi, 0), exp(nz * nphi, 0);
    int mirror = 0;
    for (int i = 0; i < n; ++i) {
      BsdfSample s;
      ASSERT_TRUE(
          bsdf.sample(sampleValue(SamplerKind::Independent, i, 0, 7, 1), uniform2(i, 1), s));
      for (int k = 0; k < kLanes; ++k) ASSERT_FLOAT_EQ(s.weight[k], rho[k]);
      if (s.specular) {
        ++mirror;
        EXPECT_NEAR(dot(s.wi, reflect(wo, ng)), 1.0f, 1e-5f);
        continue;
      }
      EXPECT_NEAR(s.pdf, bsdf.pdf(s.wi), 1e-4f * s.pdf);
      const int iz = std::min(nz - 1, static_cast<int>(s.wi.z * nz));
      double phi = std::atan2(s.wi.y, s.wi.x) + kPi;
      obs[iz * nphi + std::min(nphi - 1, static_cast<int>(phi / (2 * kPi) * nphi))] += 1;
    }
    for (int iz = 0; iz < nz; ++iz) // integral of r cos/pi over the cell, exact in cos theta
      for (int ip = 0; ip < nphi; ++ip) {
        const double z0 = double(iz) / nz, z1 = double(iz + 1) / nz;
        exp[iz * nphi + ip] = r * (z1 * z1 - z0 * z0) / 2 / kPi * (2 * kPi / nphi) * n;
      }
    const auto [stat, dof] = test::chiSquare(obs, exp);
    EXPECT_LT(test::chiSquareZ(stat, dof), 4.0) << "r " << r;
    const double pMirror = 1 - r;
    EXPECT_NEAR(mirror, pMirror * n, 5 * std::sqrt(n * pMirror * (1 - pMirror)) + 1e-9)
        << "r " << r;
  }
}

TEST(Bsdf, MixtureEvalIsReciprocalAndBelowSurfaceIsBlack) {
  const SampledWavelengths lambda = someWavelengths();
  const SampledSpectrum rho = SampledSpectrum::filled(0.6f);
  const Material m = mixture(0.4f);
  const Vec3 a = normalize(Vec3(0.2f, 0.1f, 0.9f)), b = normalize(Vec3(-0.5f, 0.3f, 0.4f));
  const SurfaceBsdf fromA(m, lambda, rho, Vec3(0, 0, 1), a),
      fromB(m, lambda, rho, Vec3(0, 0, 1), b);
  EXPECT_NEAR(fromA.f(b)[0] / b.z, fromB.f(a)[0] / a.z, 1e-6f);
  EXPECT_NEAR(fromA.f(b)[0], 0.4f * 0.6f / static_cast<float>(kPi) * b.z, 1e-6f);
  EXPECT_EQ(fromA.f(Vec3(0, 0, -1))[0], 0.0f);
  // Seen from below, the opaque surface scatters on its lower side.
  const SurfaceBsdf below(m, lambda, rho, Vec3(0, 0, 1), -a);
  EXPECT_GT(below.f(Vec3(0, 0, -1))[0], 0.0f);
}

// Albedo (energy, no radiance scaling) of every material for many directions: <= 1, and
// exactly rho for a lossless surface.
TEST(Bsdf, AlbedoNeverExceedsOne) {
  const SampledWavelengths lambda = someWavelengths();
  IorModel bk7;
  namedGlass("bk7", bk7);
  const std::vector<Material> materials{mixture(1),
                                        mixture(0.5f),
                                        mixture(0),
                                        dielectric(IorModel::constant(1.5)),
                                        dielectric(IorModel::constant(2.418)),
                                        dielectric(bk7)};
  for (const Material& m : materials) {
    for (float cosTheta : {1.0f, 0.7f, 0.3f, 0.05f, -0.05f, -0.3f, -0.7f, -1.0f}) {
      const Vec3 wo = direction(cosTheta, 0.4f);
      const SurfaceBsdf bsdf(m, lambda, SampledSpectrum::filled(1.0f), Vec3(0, 0, 1), wo,
                             TransportMode::Energy);
      const int n = 20000;
      double sum = 0;
      for (int i = 0; i < n; ++i) {
        BsdfSample s;
        if (!bsdf.sample(sampleValue(SamplerKind::Independent, i, 0, 2, 3), uniform2(i, 3), s))
          continue;
        sum += s.weight[0];
      }
      EXPECT_NEAR(sum / n, 1.0, 1e-5) << "kind " << int(m.kind) << " cos " << cosTheta;
    }
  }
}

// Smooth dielectric: reflection chosen with probability F (exact Fresnel), directions obey
// the law of reflection and Snell's law, total internal reflection beyond the critical angle.
TEST(Bsdf, DielectricFresnelSnellAndTotalInternalReflection) {
  const SampledWavelengths lambda = someWavelengths();
  const Material glass = dielectric(IorModel::constant(1.5));
  const float eta = 1.5f;
  for (float cosTheta : {0.95f, 0.6f, 0.2f, -0.95f, -0.8f, -0.6f, -0.2f}) {
    const Vec3 wo = direction(cosTheta, 1.1f);
    const bool entering = cosTheta > 0;
    const float etaRel = entering ? eta : 1 / eta;
    const float F = fresnelDielectric(std::abs(cosTheta), etaRel);
    const SurfaceBsdf bsdf(glass, lambda, SampledSpectrum::filled(1.0f), Vec3(0, 0, 1), wo);
    const int n = 40000;
    int reflected = 0;
    for (int i = 0; i < n; ++i) {
      BsdfSample s;
      ASSERT_TRUE(
          bsdf.sample(sampleValue(SamplerKind::Independent, i, 0, 4, 1), uniform2(i, 5), s));
      EXPECT_TRUE(s.specular);
      const float sinO = std::sqrt(1 - cosTheta * cosTheta);
      const float sinI = std::sqrt(std::max(0.0f, 1 - s.wi.z * s.wi.z));
      if (s.wi.z * cosTheta > 0) {
        ++reflected;
        EXPECT_NEAR(s.wi.z, cosTheta, 1e-5f); // mirror about the normal
        EXPECT_NEAR(s.weight[0], 1.0f, 1e-5f);
        EXPECT_EQ(s.eta, 1.0f);
      } else {
        EXPECT_LT(s.wi.z * cosTheta, 0.0f);                     // other side
        EXPECT_NEAR(sinO, etaRel * sinI, 1e-4f);                // Snell
        EXPECT_NEAR(s.weight[0], 1 / (etaRel * etaRel), 1e-4f); // radiance scaling
        EXPECT_NEAR(s.eta, etaRel, 1e-6f);                      // what Russian roulette divides out
      }
    }
    const double sd = std::sqrt(n * F * (1 - F));
    EXPECT_NEAR(reflected, F * n, 5 * sd + 1e-9) << cosTheta;
    if (!entering && std::sqrt(1 - cosTheta * cosTheta) * eta > 1) {
      EXPECT_EQ(reflected, n); // total internal reflection
    }
  }
  // Normal incidence on glass: ((n - 1) / (n + 1))^2 = 0.04.
  EXPECT_NEAR(fresnelDielectric(1.0f, 1.5f), 0.04f, 1e-6f);
  // Brewster's angle: p-polarised reflectance vanishes, so F = rs^2 / 2.
  const float cb = std::cos(std::atan(1.5f));
  const float ct = std::sqrt(1 - (1 - cb * cb) / 2.25f), rs = (cb - 1.5f * ct) / (cb + 1.5f * ct);
  EXPECT_NEAR(fresnelDielectric(cb, 1.5f), 0.5f * rs * rs, 1e-6f);
}

TEST(Bsdf, DispersionTerminatesSecondariesOnlyOnRefraction) {
  IorModel bk7;
  ASSERT_TRUE(namedGlass("bk7", bk7));
  const SampledWavelengths lambda = someWavelengths();
  const Material glass = dielectric(bk7); // SurfaceBsdf refers to it
  const SurfaceBsdf bsdf(glass, lambda, SampledSpectrum::filled(1.0f), Vec3(0, 0, 1),
                         direction(0.8f, 0.3f));
  bool sawReflection = false, sawRefraction = false;
  for (int i = 0; i < 200 && !(sawReflection && sawRefraction); ++i) {
    BsdfSample s;
    ASSERT_TRUE(bsdf.sample(static_cast<float>(i) / 200.0f, {0.5f, 0.5f}, s));
    if (s.wi.z < 0) {
      sawRefraction = true;
      EXPECT_TRUE(s.terminateSecondary);
      for (int k = 1; k < kLanes; ++k) EXPECT_EQ(s.weight[k], 0.0f);
      EXPECT_NEAR(s.weight[0], 1 / std::pow(static_cast<float>(bk7.at(lambda.lambda[0])), 2.0f),
                  1e-4f);
    } else {
      sawReflection = true;
      EXPECT_FALSE(s.terminateSecondary);
    }
  }
  EXPECT_TRUE(sawReflection && sawRefraction);
  SampledSpectrum beta;
  for (int k = 0; k < kLanes; ++k) beta[k] = 0.5f + static_cast<float>(k);
  const SampledSpectrum hero = heroOnly(beta);
  EXPECT_FLOAT_EQ(hero[0], 0.5f * kLanes); // with the film's 1 / (kLanes pdf): 1 / pdf
  for (int k = 1; k < kLanes; ++k) EXPECT_EQ(hero[k], 0.0f);
}

} // namespace
} // namespace nx

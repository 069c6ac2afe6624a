// Every material kind, made as a scene file makes it, passes the same checks: albedo at most 1
// over a grid of directions down to grazing (energy, no radiance scaling), finite values
// everywhere, specular lobes, chi-square of sampling against the pdf, weights f / pdf and
// reciprocity. The cases come from the registry (every registered kind alone, and with each
// of its parameters' declared example, and each kind's declared examples: a new kind is
// checked without a line here); every scattering model of NX_SCATTERING_MODELS must be reached
// by them.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "core/params/material_parameters.h"
#include "integrators/gradients/geometry_gradients.h"
#include "integrators/materials/bsdf.h"
#include "integrators/materials/material_kind.h"
#include "integrators/sampling.h"
#include "integrators/scene_reader.h"
#include "support/direction_chi_square.h"
#include "support/render_checks.h"
#include "support/statistics.h"

namespace nx {
namespace {

// Every scattering model once, in the registry's order (NX_SCATTERING_MODELS).
constexpr MaterialKind kKinds[] = {
#define NX_MODEL_KIND(name) MaterialKind::name,
    NX_SCATTERING_MODELS(NX_MODEL_KIND)
#undef NX_MODEL_KIND
};
constexpr size_t kKindCount = std::size(kKinds);

// The lanes' wavelengths the checks use: spread over the visible range and beyond.
SampledWavelengths conformanceWavelengths() {
  SampledWavelengths lambda;
  for (int i = 0; i < kLanes; ++i) {
    lambda.lambda[i] = 420.0f + 70.0f * static_cast<float>(i);
    lambda.pdf[i] = 1.0f / 300.0f;
  }
  return lambda;
}

Vec3 direction(float cosTheta, float phi) {
  const float s = std::sqrt(std::max(0.0f, 1 - cosTheta * cosTheta));
  return {s * std::cos(phi), s * std::sin(phi), cosTheta};
}

// A sphere made of one way of reaching a kind, and the material's reflectance at the lanes.
struct KindCase {
  RenderScene scene;
  SampledSpectrum rho;
  const Material& material() const {
    return scene.materials[scene.shapes(ShapeKind::Sphere)[0].material];
  }
};

KindCase kindCase(const std::string& body, const SampledWavelengths& lambda) {
  KindCase c{resolveRenderScene(parseScene(
                 sceneText("<xres>4</xres><yres>4</yres><mode>spectral_mcpt</mode>",
                           "<position>0,0,-5</position><look_at>0,0,0</look_at>",
                           "<sphere><center>0,0,0</center><radius>1</radius>" + body + "</sphere>"),
                 "t.scn")),
             {}};
  c.material().reflectance.evaluate(lambda.lambda, c.rho);
  return c;
}

std::string element(const char* name) {
  return "<" + std::string(name) + ">" + materialParameter(name)->example + "</" + name + ">";
}

bool builds(const std::string& body) {
  try {
    (void)kindCase(body, conformanceWavelengths());
    return true;
  } catch (const Error&) {
    return false;
  }
}

// The registry's cases: every kind with each parameter it takes set to the parameter's declared
// example: alone, else beside one other of the kind's parameters (a matte needs its colour, an
// alpha_u its alpha_v), the first such pair that builds; and the kind with none where it builds.
std::vector<std::string> registryBodies() {
  std::vector<std::string> out;
  for (const MaterialKindSpec* k : materialKinds()) {
    const std::string kind = "<material>" + std::string(k->name) + "</material>";
    if (builds(kind)) out.push_back(kind);
    for (const KindParameter& p : k->params) {
      std::string body = kind + element(p.name);
      for (size_t q = 0; q < k->params.size() && !builds(body); ++q)
        if (k->params[q].name != p.name) body = kind + element(p.name) + element(k->params[q].name);
      if (builds(body)) out.push_back(body);
    }
  }
  return out;
}

// Every case the checks run: the registry's parameter cases that build, and each kind's
// declared examples (MaterialKindSpec::examples: the ways of reaching its lobes that change
// them).
const std::vector<std::string>& conformanceBodies() {
  static const std::vector<std::string> bodies = [] {
    std::vector<std::string> out = registryBodies();
    for (const MaterialKindSpec* k : materialKinds())
      for (const char* example : k->examples)
        out.push_back("<material>" + std::string(k->name) + "</material>" + example);
    return out;
  }();
  return bodies;
}

TEST(MaterialConformance, EveryRegisteredKindAndParameterIsAmongTheCases) {
  const std::vector<std::string>& bodies = conformanceBodies();
  for (const MaterialKindSpec* k : materialKinds()) {
    const std::string kind = "<material>" + std::string(k->name) + "</material>";
    int cases = 0;
    for (const std::string& b : bodies) cases += b.rfind(kind, 0) == 0;
    EXPECT_GE(cases, 1) << k->name << ": no case of the kind builds";
    // Each parameter the kind takes is checked in at least one case of the kind.
    for (const KindParameter& p : k->params) {
      bool found = false;
      for (const std::string& b : bodies)
        found = found || (b.rfind(kind, 0) == 0 &&
                          b.find("<" + std::string(p.name) + ">") != std::string::npos);
      EXPECT_TRUE(found) << k->name << " with <" << p.name << ">: no case builds";
    }
  }
  // Each evaluation (MaterialKind) is reached by the registry's cases too.
  const SampledWavelengths lambda = conformanceWavelengths();
  std::vector<bool> reached(kKindCount, false);
  for (const std::string& body : registryBodies()) try {
      const MaterialKind got = kindCase(body, lambda).material().kind;
      for (size_t i = 0; i < kKindCount; ++i) reached[i] = reached[i] || kKinds[i] == got;
    } catch (const Error&) {
    }
  for (size_t i = 0; i < kKindCount; ++i)
    EXPECT_TRUE(reached[i]) << "scattering model " << i
                            << " of NX_SCATTERING_MODELS: no case reaches it";
}

TEST(MaterialConformance, EveryKindKeepsEnergyAndStaysFinite) {
  const SampledWavelengths lambda = conformanceWavelengths();
  {
    for (const std::string& body : conformanceBodies()) {
      const KindCase c = kindCase(body, lambda);
      const Material& m = c.material();
      const SampledSpectrum& rho = c.rho;
      for (float cosTheta : {1.0f, 0.6f, 0.2f, 0.02f, -0.02f, -0.2f, -0.6f, -1.0f}) {
        const Vec3 wo = direction(cosTheta, 0.7f), n(0, 0, 1);
        const SurfaceBsdf bsdf(m, lambda, rho, n, wo, TransportMode::Energy);
        const int count = 20000;
        std::vector<double> sum(kLanes, 0), sumSq(kLanes, 0);
        for (int i = 0; i < count; ++i) {
          BsdfSample s;
          if (!bsdf.sample(sampleValue(SamplerKind::Independent, i, 0, 2, 3),
                           samplePair(SamplerKind::Independent, i, 0, 3, 5), s))
            continue;
          for (int k = 0; k < kLanes; ++k) {
            ASSERT_TRUE(std::isfinite(s.weight[k])) << body << " cos " << cosTheta;
            ASSERT_GE(s.weight[k], 0.0f) << body << " cos " << cosTheta;
            sum[k] += s.weight[k], sumSq[k] += double(s.weight[k]) * s.weight[k];
          }
          for (int k = 0; k < kLanes; ++k) ASSERT_TRUE(std::isfinite(bsdf.f(s.wi)[k])) << body;
        }
        for (int k = 0; k < kLanes; ++k) {
          const double mean = sum[k] / count,
                       se = std::sqrt(std::max(0.0, sumSq[k] / count - mean * mean) / count);
          // Albedo at most 1 within 5 standard errors (and float rounding).
          EXPECT_LE(mean, 1.0 + 5 * se + 1e-5)
              << body << " cos " << cosTheta << " lane " << lambda.lambda[k] << " nm";
        }
      }
    }
  }
}

// What Whitted ray tracing follows (every delta lobe with its full weight) is what the path
// tracer's sampling draws on average: over a fine grid of lobe choices, the specular samples'
// weights summed per direction and divided by the count equal each lobe's weight (the choice
// probability cancels its 1/p), lane by lane (the hero lane alone after a dispersive
// refraction, whose secondaries the sample terminates).
TEST(MaterialConformance, SpecularLobesAreWhatSamplingDrawsOnAverage) {
  const SampledWavelengths lambda = conformanceWavelengths();
  int lobesChecked = 0;
  for (const std::string& body : conformanceBodies()) {
    const KindCase c = kindCase(body, lambda);
    const Material& m = c.material();
    const SampledSpectrum& rho = c.rho;
    for (float cosTheta : {1.0f, 0.5f, 0.1f, -0.3f, -0.9f}) {
      const Vec3 wo = direction(cosTheta, 0.7f), n(0, 0, 1);
      const SurfaceBsdf bsdf(m, lambda, rho, n, wo);
      SpecularLobe lobes[2];
      const int count = bsdf.specularLobes(lobes);
      EXPECT_EQ(count > 0, (bsdf.lobes() & (kSpecularReflection | kSpecularTransmission)) != 0)
          << body;
      const int grid = 20000;
      SampledSpectrum sum[2], largest[2]; // largest: one sample's weight, per lobe and lane
      for (int i = 0; i < grid; ++i) {
        BsdfSample s;
        if (!bsdf.sample((static_cast<float>(i) + 0.5f) / grid, {0.3f, 0.6f}, s) || !s.specular)
          continue;
        int which = -1;
        for (int l = 0; l < count; ++l)
          if (dot(s.wi, lobes[l].wi) > 1 - 1e-5f) which = l;
        ASSERT_GE(which, 0) << body << " cos " << cosTheta << ": a specular sample in no lobe";
        sum[which] += s.weight * (1.0f / grid);
        for (int k = 0; k < kLanes; ++k)
          largest[which][k] = std::max(largest[which][k], s.weight[k]);
      }
      for (int l = 0; l < count; ++l)
        for (int k = 0; k < (lobes[l].heroOnly ? 1 : kLanes); ++k) {
          const float want = lobes[l].weight[k];
          // The grid of uLobe draws a lobe of probability P in P grid +- 1 of its points: one
          // point's weight is the resolution (a lobe of P = 1e-4 is drawn 2 times in 20000).
          EXPECT_NEAR(sum[l][k], want, 0.01f * want + 1e-4f + largest[l][k] / grid)
              << body << " cos " << cosTheta << " lobe " << l << " lane " << k;
          ++lobesChecked;
        }
    }
  }
  EXPECT_GT(lobesChecked, 100);
}

// Every kind's non-specular sampling follows its pdf (chi-square over the sphere), its weights
// are f / pdf (what MIS and Russian roulette rely on), and its reflection is reciprocal:
// f(wo, wi) = f(wi, wo), compared as f |cos wi| / |cos wi| both ways, over every case.
TEST(MaterialConformance, SamplingFollowsThePdfWeightsAreFOverPdfReflectionIsReciprocal) {
  const SampledWavelengths lambda = conformanceWavelengths();
  int checked = 0;
  for (const std::string& body : conformanceBodies()) {
    const KindCase c = kindCase(body, lambda);
    const Material& m = c.material();
    const SampledSpectrum& rho = c.rho;
    const Vec3 n(0, 0, 1);
    for (const Vec3& wo :
         {normalize(Vec3(0.3f, 0.1f, 0.9f)), normalize(Vec3(-0.8f, 0.3f, 0.25f))}) {
      SCOPED_TRACE(body + " wo.z " + std::to_string(wo.z));
      const SurfaceBsdf bsdf(m, lambda, rho, n, wo, TransportMode::Energy);
      if (!bsdf.hasNonSpecular()) continue;
      uint32_t k = 0;
      int weightChecks = 0;
      auto draw = [&](Sample2 u) {
        BsdfSample s;
        if (!bsdf.sample(uniform2(700000 + k++).u, u, s) || s.specular) return Vec3(0, 0, 0);
        // The weight is f |cos| / pdf on the hero lane (the one every sample keeps); a
        // dispersive transmission's f counts the hero for all lanes (kLanes x; see
        // SurfaceBsdf::setHeroAlone), its sample's weight the hero alone.
        const float f = bsdf.f(s.wi)[0] / (s.terminateSecondary ? kLanes : 1), pdf = bsdf.pdf(s.wi);
        if (pdf > 1e-3f && f > 1e-6f && weightChecks < 2000) {
          EXPECT_NEAR(s.weight[0], f / pdf, 2e-3f * (f / pdf) + 1e-6f);
          ++weightChecks;
        }
        return s.wi;
      };
      // The expected counts integrate the pdf over 40 x 40 cells (8 x 8 points each): a lobe
      // narrower than a cell is beyond that quadrature; its weights are still checked. A GGX
      // lobe of alpha below 0.1 is; so is a rough dielectric's transmitted lobe when the index
      // is near 1: refraction narrows the microfacets' spread by about |eta - 1| / eta (index
      // 1.02 and alpha 0.2: 0.004 rad).
      const float alpha = std::max(m.alphaU, m.alphaV);
      const float eta = static_cast<float>(m.ior.at(lambda.lambda[0]));
      const bool narrowTransmission = m.kind == MaterialKind::Dielectric &&
                                      alpha * std::abs(eta - 1) / std::max(eta, 1.0f) < 0.02f;
      if ((alpha > 0 && alpha < 0.1f) || (alpha > 0 && narrowTransmission)) {
        for (uint32_t i = 0; i < 20000; ++i) (void)draw(uniform2(i));
      } else {
        expectDirectionsFollowPdf(
            draw, [&](const Vec3& wi) { return bsdf.pdf(wi); }, 100000);
      }
      EXPECT_GT(weightChecks, 0);
      ++checked;
    }
    // Reciprocity of reflection (non-fluorescent surfaces: re-radiation shifts wavelengths).
    if (m.reradiation) continue;
    for (uint32_t i = 0; i < 64; ++i) {
      auto dir = [](Sample2 u) {
        const float z = 0.05f + 0.95f * u.u, r = std::sqrt(1 - z * z);
        const float p = 2 * static_cast<float>(kPi) * u.v;
        return Vec3(r * std::cos(p), r * std::sin(p), z);
      };
      const Vec3 a = dir(uniform2(2 * i)), b = dir(uniform2(2 * i + 1));
      const SurfaceBsdf fa(m, lambda, rho, n, a, TransportMode::Energy),
          fb(m, lambda, rho, n, b, TransportMode::Energy);
      for (int lane = 0; lane < kLanes; ++lane) {
        const float ab = fa.f(b)[lane] / b.z, ba = fb.f(a)[lane] / a.z;
        EXPECT_NEAR(ab, ba, 1e-3f * std::max(ab, ba) + 1e-6f) << body << " lane " << lane;
      }
    }
  }
  EXPECT_GT(checked, 8);
}

// d g / d s at 0 of a smooth function of one variable, per lane, by Ridders' extrapolation
// (Ridders 1982): central differences at steps H / 1.4^i extrapolated to a step of 0 in a
// Neville tableau, keeping the entry whose estimated error is smallest. An independent
// reference for directionalDerivative: many steps, evaluated in double where they combine,
// and an error estimate of its own.
struct RiddersDerivative {
  double value = 0, error = 1e300;
};
template <class At>
std::array<RiddersDerivative, kLanes> riddersDerivative(At&& at, double H) {
  constexpr int kSteps = 12;
  constexpr double kShrink = 1.4, kShrink2 = kShrink * kShrink;
  std::array<RiddersDerivative, kLanes> out;
  double a[kSteps][kSteps][kLanes];
  double h = H;
  for (int i = 0; i < kSteps; ++i, h /= kShrink) {
    const SampledSpectrum p = at(static_cast<float>(h)), m = at(static_cast<float>(-h));
    for (int k = 0; k < kLanes; ++k) a[0][i][k] = (double(p[k]) - double(m[k])) / (2 * h);
    double fac = kShrink2;
    for (int j = 1; j <= i; ++j, fac *= kShrink2)
      for (int k = 0; k < kLanes; ++k) {
        a[j][i][k] = (a[j - 1][i][k] * fac - a[j - 1][i - 1][k]) / (fac - 1);
        const double e = std::max(std::abs(a[j][i][k] - a[j - 1][i][k]),
                                  std::abs(a[j][i][k] - a[j - 1][i - 1][k]));
        if (e < out[k].error) out[k] = {a[j][i][k], e};
      }
  }
  return out;
}

// Every kind's BSDF derivatives in its arguments (what shape gradients differentiate:
// geometry_gradients.h's directionalDerivative, at the steps bsdfDerivativeSteps gives the kind)
// agree with Ridders' extrapolation (above), over every case, at directions the kind's own
// sampling draws, for the normals turning, wo turning, wi turning and all three at once. The
// error counted is |d - ref| / max(|ref|, f) per radian. A reference whose own error estimate
// exceeds a tenth of the tolerance (at a kink: total internal reflection, the horizon) is not
// counted, and most points of every case must count. A float step of 1e-3 at roughness 0.01
// fails the median bound (docs/inverse.md, "Accuracy of the interior term").
TEST(MaterialConformance, DerivativesInDirectionsAndNormalsMatchAnExtrapolatedReference) {
  const SampledWavelengths lambda = conformanceWavelengths();
  constexpr double kMedianBound = 5e-4, kTailBound = 2e-2; // 99th percentile
  int bodiesChecked = 0;
  for (const std::string& body : conformanceBodies()) {
    const KindCase c = kindCase(body, lambda);
    const Material& m = c.material();
    const Vec3 n(0, 0, 1), dpdu(1, 0, 0);
    const BsdfDerivativeSteps step = bsdfDerivativeSteps(m);
    // The lobe's width in its directions: the roughness (a transmitted lobe narrowed by
    // |eta - 1| / eta), where the reference's steps start.
    const float width = std::max(m.alphaU, m.alphaV) > 0 ? std::min(m.alphaU, m.alphaV) : 1.0f;
    float narrowed = width; // in wo and wi
    if (m.kind == MaterialKind::Dielectric) {
      const float eta = static_cast<float>(m.ior.at(550));
      narrowed *= std::min(1.0f, std::abs(eta - 1) / eta);
    }
    auto value = [&](const Vec3& ng, const Vec3& ns, const Vec3& wo, const Vec3& wi) {
      SurfaceBsdf b(m, lambda, c.rho, ng, ns, wo);
      b.orient(dpdu);
      return b.f(wi);
    };
    std::vector<double> errors;
    int points = 0, counted = 0;
    for (const Vec3& wo :
         {normalize(Vec3(0.3f, 0.1f, 0.9f)), normalize(Vec3(-0.7f, 0.4f, 0.5f)),
          normalize(Vec3(0.2f, -0.9f, 0.3f)), normalize(Vec3(0.4f, 0.2f, -0.8f))}) {
      SurfaceBsdf bsdf(m, lambda, c.rho, n, wo);
      bsdf.orient(dpdu);
      if (!bsdf.hasNonSpecular()) continue;
      for (uint32_t i = 0; i < 24; ++i) {
        BsdfSample s;
        if (!bsdf.sample(uniform2(900 + i).u, uniform2(i), s) || s.specular) continue;
        const Vec3 wi = s.wi;
        const SampledSpectrum f = value(n, n, wo, wi);
        // Unit motions: perpendicular to what they turn.
        const Vec3 tn = normalize(Vec3(0.6f, -0.8f, 0.0f));
        const Vec3 to = normalize(cross(wo, Vec3(0.3f, 0.5f, 0.8f)));
        const Vec3 ti = normalize(cross(wi, Vec3(-0.5f, 0.7f, 0.2f)));
        const Vec3 none;
        const std::array<std::array<Vec3, 4>, 4> motions{{{tn, tn, none, none},
                                                          {none, none, to, none},
                                                          {none, none, none, ti},
                                                          {tn, tn, to, ti}}};
        for (size_t j = 0; j < motions.size(); ++j) {
          const auto& mv = motions[j];
          const double start = 0.5 * (j == 0 ? width : narrowed);
          const SampledSpectrum d =
              directionalDerivative(value, step, n, n, wo, wi, mv[0], mv[1], mv[2], mv[3]);
          const float scale =
              std::max({length(mv[0]), length(mv[1]), length(mv[2]), length(mv[3])});
          const auto ref = riddersDerivative(
              [&](float h) {
                return value(normalize(n + mv[0] * h), normalize(n + mv[1] * h),
                             normalize(wo + mv[2] * h), normalize(wi + mv[3] * h));
              },
              std::min(0.05, start) / scale);
          for (int k = 0; k < kLanes; ++k) {
            if (!(f[k] > 1e-6f)) continue;
            ++points;
            const double norm = std::max(std::abs(ref[k].value), double(f[k]));
            if (!(ref[k].error < 0.1 * kMedianBound * norm)) continue;
            ++counted;
            ASSERT_TRUE(std::isfinite(d[k])) << body;
            errors.push_back(std::abs(d[k] - ref[k].value) / norm);
          }
        }
      }
    }
    if (points == 0) continue;
    SCOPED_TRACE(body);
    EXPECT_GE(counted, points / 3) << "the reference resolves too few points";
    std::sort(errors.begin(), errors.end());
    const double median = errors.empty() ? 1 : errors[errors.size() / 2];
    const double tail = errors.empty() ? 1 : errors[errors.size() * 99 / 100];
    std::printf("derivative error  median %.1e  99%% %.1e  max %.1e  (%d of %d points)  %s\n",
                median, tail, errors.empty() ? 1.0 : errors.back(), counted, points, body.c_str());
    EXPECT_LT(median, kMedianBound);
    EXPECT_LT(tail, kTailBound);
    ++bodiesChecked;
  }
  EXPECT_GT(bodiesChecked, 10);
}

} // namespace
} // namespace nx

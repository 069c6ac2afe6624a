// The light kinds' registry against the scene format, generated from the registry (a new kind
// is covered without editing this file): every kind builds from its declared examples, refuses
// what it does not declare at the element's line, and is found by its name.

#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "core/sampler.h"
#include "integrators/render_scene.h"
#include "integrators/scene_reader.h"
#include "io/spectral_exr.h"
#include "support/constant_map.h"
#include "support/direction_chi_square.h"
#include "support/errors.h"
#include "support/render_checks.h"
#include "support/statistics.h"

namespace nx {
namespace {

std::string lightScene(const std::string& light) {
  return "<scene>\n<settings><xres>4</xres><yres>4</yres><mode>spectral_mcpt</mode></settings>\n"
         "<camera><position>0,1,-5</position><look_at>0,0,0</look_at></camera>\n"
         "<plane><normal>0,1,0</normal><distance>0</distance><material>matte</material>"
         "<reflectance>0.5</reflectance></plane>\n" +
         light + "\n</scene>\n";
}

// A spectral EXR (a constant one) where a file parameter's example names one.
std::string exampleFile(const std::string& example) {
  return test::writeConstantMap(example, 4, 2, "350:1050:100", 0.5f);
}

// Every parameter the kind declares, at its example (a scale as its spectrum's attribute).
std::string exampleLight(const LightKindSpec& kind) {
  std::string body;
  for (const LightParameter& p : kind.params()) {
    const std::string name = p.spec.name;
    if (name.ends_with("_scale") || name == "emission_at") continue; // attributes of <emission>
    if (p.spec.type == ParamType::File) {
      body += "<" + name + ">" + exampleFile(p.spec.example) + "</" + name + ">";
      continue;
    }
    std::string attributes;
    for (const char* a : {"scale", "at"})
      if (const LightParameter* s = lightParameter(kind, name + "_" + a))
        attributes += std::string(" ") + a + "=\"" + s->spec.example + "\"";
    body += "<" + name + attributes + ">" + p.spec.example + "</" + name + ">";
  }
  return std::string("<light type=\"") + kind.name + "\">" + body + "</light>";
}

TEST(LightKinds, RegistryAgreesWithItsDeclarations) {
  std::set<std::string> names;
  for (const LightKindSpec& kind : lightKinds()) {
    SCOPED_TRACE(kind.name);
    EXPECT_TRUE(names.insert(kind.name).second);
    EXPECT_EQ(findLightKind(kind.name), &kind);
    std::set<std::string> params;
    for (const LightParameter& p : kind.params()) {
      EXPECT_TRUE(params.insert(p.spec.name).second) << p.spec.name << " declared twice";
      EXPECT_GT(std::string(p.spec.doc).size(), 5u) << p.spec.name;
      EXPECT_GT(std::string(p.spec.example).size(), 0u) << p.spec.name;
      if (std::string(p.spec.name).ends_with("_scale")) {
        const std::string base(p.spec.name, std::string(p.spec.name).size() - 6);
        ASSERT_NE(lightParameter(kind, base), nullptr) << "a scale of nothing";
      }
    }
  }
  EXPECT_EQ(findLightKind("lamp"), nullptr);
  EXPECT_TRUE(names.count("point")) << "Niixtracer's <light> is a point light";
}

TEST(LightKinds, EveryKindBuildsFromItsExamplesAndItsLightShines) {
  for (const LightKindSpec& kind : lightKinds()) {
    SCOPED_TRACE(kind.name);
    const std::string text = lightScene(exampleLight(kind));
    const RenderScene scene = buildRenderScene(parseScene(text, "t.scn"));
    ASSERT_EQ(scene.lights.size(), 1u);
    const double power = std::visit([](const auto& l) { return l.power(); }, scene.lights[0]);
    EXPECT_GT(power, 0);
    EXPECT_TRUE(std::isfinite(power));
  }
}

// What a light sends, integrated independently of the power it declares (which the light
// sampler chooses lights by): a positioned light's intensity I = L d^2 (its sample's radiance
// times the squared distance) over the sphere of directions around it, read from points all
// around; an infinite light's radiance over directions by its own sampling, E[L / pdf]; both
// over the traced range by stratified wavelengths. Every kind at its declared example, within
// 4.5 standard errors (a million samples: 2% for the example spot light) plus 0.2% (the declared
// power is a trapezoid rule on a 1 nm grid: a spectrum's steps, a table's ends, move it by up to
// half a nanometre's worth; a missing factor, a wrong cone or a lost falloff are far larger).
TEST(LightKinds, EveryKindsPowerIsTheIntegralOfWhatItSends) {
  constexpr uint32_t kSamples = 1000000;
  const double range = kTraceMaxNm - kTraceMinNm;
  for (const LightKindSpec& kind : lightKinds()) {
    SCOPED_TRACE(kind.name);
    const RenderScene scene = buildRenderScene(parseScene(lightScene(exampleLight(kind)), "t.scn"));
    ASSERT_EQ(scene.lights.size(), 1u);
    std::visit(
        [&](const auto& light) {
          using Light = std::decay_t<decltype(light)>;
          auto u = [](uint32_t i, uint32_t dim) {
            return sampleValue(SamplerKind::Independent, i, 0, dim, 11);
          };
          auto direction = [&](uint32_t i) {
            const double z = 1 - 2 * static_cast<double>(u(i, 0));
            const double phi = 2 * kPi * static_cast<double>(u(i, 1));
            const double r = std::sqrt(std::max(0.0, 1 - z * z));
            return Vec3(static_cast<float>(r * std::cos(phi)),
                        static_cast<float>(r * std::sin(phi)), static_cast<float>(z));
          };
          auto wavelengths = [&](uint32_t i) {
            SampledWavelengths lambda;
            for (int k = 0; k < kLanes; ++k) {
              lambda.lambda[static_cast<size_t>(k)] = static_cast<float>(
                  kTraceMinNm + range * (k + static_cast<double>(u(i, 2))) / kLanes);
              lambda.pdf[static_cast<size_t>(k)] = static_cast<float>(1 / range);
            }
            return lambda;
          };
          // A positioned light's point: where its samples end, seen from anywhere it shines.
          Vec3 centre;
          if constexpr (!Light::kInfinite) {
            bool found = false;
            for (uint32_t i = 0; i < 1000 && !found; ++i) {
              LightSample out;
              found = light.sample(direction(i) * 50.0f, {}, wavelengths(i), out);
              if (found) centre = out.p;
            }
            ASSERT_TRUE(found) << "it shines nowhere";
          }
          test::RunningStats power;
          for (uint32_t i = 0; i < kSamples; ++i) {
            const SampledWavelengths lambda = wavelengths(i);
            LightSample out;
            double mean = 0;
            if constexpr (Light::kInfinite) {
              if (light.sample(Vec3(), {u(i, 3), u(i, 4)}, lambda, out) && out.pdf > 0) {
                for (int k = 0; k < kLanes; ++k) mean += out.radiance[k] / out.pdf / kLanes;
                mean *= kPi * range; // power(1): pi r^2 times the integral of L, r = 1
              }
            } else {
              const float distance = 3;
              if (light.sample(centre + direction(i) * distance, {}, lambda, out)) {
                const double d2 = static_cast<double>(out.distance) * out.distance;
                for (int k = 0; k < kLanes; ++k) mean += out.radiance[k] * d2 / kLanes;
                mean *= 4 * kPi * range;
              }
            }
            power.add(mean);
          }
          const double declared = light.power(1.0);
          EXPECT_NEAR(power.mean, declared, 4.5 * power.standardError() + 2e-3 * declared)
              << "integrated " << power.mean << " +- " << power.standardError();
        },
        scene.lights[0]);
  }
}

// Every infinite kind at its declared example: the directions its sampling draws follow the
// density it reports (chi-square over equal-area cells; test_environment_light.cpp checks the
// environment map with a non-uniform map as well).
TEST(LightKinds, EveryInfiniteKindsSamplingFollowsItsPdf) {
  int infinite = 0;
  SampledWavelengths lambda;
  for (int k = 0; k < kLanes; ++k) {
    lambda.lambda[static_cast<size_t>(k)] = 400.0f + 40.0f * static_cast<float>(k);
    lambda.pdf[static_cast<size_t>(k)] = 1.0f / 300.0f;
  }
  for (const LightKindSpec& kind : lightKinds()) {
    SCOPED_TRACE(kind.name);
    const RenderScene scene = buildRenderScene(parseScene(lightScene(exampleLight(kind)), "t.scn"));
    std::visit(
        [&](const auto& light) {
          if constexpr (std::decay_t<decltype(light)>::kInfinite) {
            ++infinite;
            expectDirectionsFollowPdf(
                [&](Sample2 u) {
                  LightSample out;
                  return light.sample(Vec3(), u, lambda, out) ? out.wi : Vec3();
                },
                [&](const Vec3& w) { return static_cast<double>(light.pdf(w)); });
          }
        },
        scene.lights[0]);
  }
  EXPECT_GE(infinite, 1) << "no infinite light kind: the check ran on nothing";
}

TEST(LightKinds, UndeclaredParametersAreRefusedAtTheirLine) {
  for (const LightKindSpec& kind : lightKinds()) {
    SCOPED_TRACE(kind.name);
    std::string light = exampleLight(kind);
    light.insert(light.size() - 8, "\n<radius>1</radius>");
    const std::string message =
        test::errorMessage([&] { (void)parseScene(lightScene(light), "t.scn"); });
    EXPECT_EQ(message.rfind("t.scn:6: expected one of <", 0), 0u) << message;
    EXPECT_NE(message.find("inside <light>, found <radius>"), std::string::npos) << message;
  }
  EXPECT_NE(test::errorMessage([&] {
              (void)parseScene(lightScene("<light type=\"lamp\"></light>"), "t.scn");
            }).find("t.scn:5: expected a light type point"),
            std::string::npos);
}

// A lamp given as measured: its spectral irradiance E on the axis at distance d
// (<emission at="d">) is an intensity I = E d^2, so a point at distance r on the axis receives
// E d^2 / r^2 (closed form of the inverse square law), for point and spot lights alike; the
// measuring distance must be positive.
TEST(LightKinds, IrradianceMeasuredAtADistanceBecomesTheIntensity) {
  for (const std::string light :
       {"<light><position>0,5,0</position><color>1,1,1</color>",
        "<light type=\"spot\"><position>0,5,0</position><look_at>0,0,0</look_at>"}) {
    SCOPED_TRACE(light);
    const RenderScene s = buildRenderScene(parseScene(
        lightScene(light + "<emission at=\"2\" scale=\"3\">0.1</emission></light>"), "t.scn"));
    SampledWavelengths lambda;
    for (int i = 0; i < kLanes; ++i)
      lambda.lambda[i] = 450.0f + 30.0f * static_cast<float>(i), lambda.pdf[i] = 1;
    for (double r : {2.0, 4.0, 5.0}) {
      LightSample out;
      const Vec3 p(0, static_cast<float>(5 - r), 0);
      ASSERT_TRUE(std::visit(
          [&](const auto& l) {
            return l.sample(p, {0.5f, 0.5f}, lambda, out);
          },
          s.lights[0]));
      for (int i = 0; i < kLanes; ++i) EXPECT_NEAR(out.radiance[i], 0.3 * 4 / (r * r), 1e-6) << r;
    }
  }
  EXPECT_NE(test::errorMessage([] {
              parseScene(lightScene("<light><position>0,5,0</position><color>1,1,1</color>"
                                    "<emission at=\"0\">0.1</emission></light>"),
                         "t.scn");
            }).find("a measuring distance in at=\"...\" within (0, 1e+12], found '0'"),
            std::string::npos);
}

} // namespace
} // namespace nx

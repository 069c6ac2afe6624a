// The light kinds' registry against the scene format, generated from the registry (a new kind
// is covered without editing this file): every kind builds from its declared examples, refuses
// what it does not declare at the element's line, and is found by its name.

#include <gtest/gtest.h>

#include <set>

#include "integrators/render_scene.h"
#include "integrators/scene_reader.h"
#include "io/spectral_exr.h"
#include "support/constant_map.h"
#include "support/errors.h"
#include "support/render_checks.h"

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

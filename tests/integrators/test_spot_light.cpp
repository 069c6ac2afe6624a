// The spot light against the closed form of a point source with its falloff: a Lambertian
// floor of albedo rho under a spot at height h, seen at horizontal distance r from below it,
// has radiance L = rho / pi * I s(cos theta) cos theta / d^2 with d^2 = h^2 + r^2,
// cos theta = h / d (the angle from the axis and the incidence angle are the same), s the
// smoothstep falloff. The camera looks straight down through a 0.5 degree field of view, so
// each image covers a patch over which L is constant to 1e-4.

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "integrators/scene_reader.h"
#include "support/errors.h"
#include "support/render_checks.h"

namespace nx {
namespace {

constexpr double kHeight = 4, kIntensity = 30, kAlbedo = 0.6;
constexpr double kCone = 30, kFalloff = 20;

std::string spotScene(double r, const std::string& light) {
  const std::string x = std::to_string(r);
  return sceneText("<xres>4</xres><yres>4</yres><mode>spectral_mcpt</mode><depth>1</depth>"
                   "<bands>400:700:100</bands>",
                   "<position>" + x + ",6,0</position><look_at>" + x +
                       ",0,0</look_at><up>0,0,1</up><fov>0.5</fov>",
                   "<plane><normal>0,1,0</normal><distance>0</distance><material>matte</material>"
                   "<reflectance>" +
                       std::to_string(kAlbedo) + "</reflectance></plane>" + light);
}

std::string spot(double cone, double falloff) {
  return "<light type=\"spot\"><position>0," + std::to_string(kHeight) +
         ",0</position><look_at>0,0,0</look_at><cone_angle>" + std::to_string(cone) +
         "</cone_angle><falloff_angle>" + std::to_string(falloff) + "</falloff_angle><emission>" +
         std::to_string(kIntensity) + "</emission></light>";
}

double smoothstepFalloff(double cosTheta) {
  const double cosEdge = std::cos(kCone * kPi / 180), cosStart = std::cos(kFalloff * kPi / 180);
  if (cosTheta >= cosStart) return 1;
  if (cosTheta <= cosEdge) return 0;
  const double t = (cosTheta - cosEdge) / (cosStart - cosEdge);
  return t * t * (3 - 2 * t);
}

Film renderSpot(double r, const std::string& light) {
  RenderOptions o;
  o.samples = 16;
  return renderText(spotScene(r, light), o).film;
}

TEST(SpotLight, FloorRadianceIsThePointSourceClosedFormWithItsFalloff) {
  // On the axis, inside the falloff start, in the smoothstep (two places) and beyond the cone.
  for (const double angle : {0.0, 12.0, 23.0, 27.0, 35.0}) {
    const double r = kHeight * std::tan(angle * kPi / 180);
    const double d2 = kHeight * kHeight + r * r, cosTheta = kHeight / std::sqrt(d2);
    const double expected =
        kAlbedo / kPi * kIntensity * smoothstepFalloff(cosTheta) * cosTheta / d2;
    const Film film = renderSpot(r, spot(kCone, kFalloff));
    for (int b = 0; b < film.bands().count(); ++b) {
      const test::RunningStats s = bandStats(film, b);
      EXPECT_NEAR(s.mean, expected, 5 * s.standardError() + 2e-3 * expected + 1e-12)
          << "angle " << angle << " band " << film.bands().centroid(b);
    }
    if (angle > 30) {
      for (int b = 0; b < film.bands().count(); ++b) EXPECT_EQ(bandStats(film, b).mean, 0.0);
    }
  }
}

// A spot whose cone is the whole lower hemisphere is the point light there.
TEST(SpotLight, WideOpenIsThePointLight) {
  const double r = 1.3;
  const Film a = renderSpot(r, spot(90, 90));
  const Film b = renderSpot(r, "<light><position>0," + std::to_string(kHeight) +
                                   ",0</position><color>1,1,1</color><emission>" +
                                   std::to_string(kIntensity) + "</emission></light>");
  for (int band = 0; band < a.bands().count(); ++band)
    EXPECT_NEAR(bandStats(a, band).mean, bandStats(b, band).mean, 1e-6 * bandStats(b, band).mean);
}

TEST(SpotLight, SceneErrors) {
  auto error = [](const std::string& light) {
    return test::errorMessage(
        [&] { (void)resolveRenderScene(parseScene(spotScene(0, light), "t.scn")); });
  };
  EXPECT_NE(error("<light type=\"spot\"><position>0,4,0</position><look_at>0,0,0</look_at>"
                  "<cone_angle>20</cone_angle><falloff_angle>25</falloff_angle>"
                  "<emission>1</emission></light>")
                .find("expected a falloff_angle at most the cone_angle (20 degrees), found 25"),
            std::string::npos);
  EXPECT_NE(error("<light type=\"spot\"><position>0,4,0</position><look_at>0,4,0</look_at>"
                  "<emission>1</emission></light>")
                .find("expected a look_at point apart from the spot light's position"),
            std::string::npos);
  EXPECT_NE(error("<light type=\"spot\"><position>0,4,0</position><look_at>0,0,0</look_at>"
                  "</light>")
                .find("expected <emission> or <color> on a spot light, found neither"),
            std::string::npos);
  EXPECT_NE(error("<light type=\"spot\"><position>0,4,0</position><look_at>0,0,0</look_at>"
                  "<cone_angle>95</cone_angle><emission>1</emission></light>")
                .find("expected a half-angle in degrees in [0.03, 90]"),
            std::string::npos);
  EXPECT_NE(error("<light type=\"spot\"><position>0,4,0</position><emission>1</emission></light>")
                .find("expected <look_at> inside <light>, found none"),
            std::string::npos);
  EXPECT_NE(error("<light type=\"spot\"><position>0,4,0</position><look_at>0,0,0</look_at>"
                  "<cone_angle>0.001</cone_angle><emission>1</emission></light>")
                .find("expected a half-angle in degrees in [0.03, 90]"),
            std::string::npos);
  const std::string unknown = error("<light type=\"lamp\"><position>0,4,0</position></light>");
  EXPECT_NE(unknown.find("expected a light type point"), std::string::npos) << unknown;
  EXPECT_NE(unknown.find("spot"), std::string::npos) << unknown;
  EXPECT_NE(unknown.find("found 'lamp'"), std::string::npos) << unknown;
  EXPECT_NE(error("<light type=\"spot\"><position>0,4,0</position><look_at>0,0,0</look_at>"
                  "<radius>1</radius><emission>1</emission></light>")
                .find("inside <light>, found <radius>"),
            std::string::npos);
}

} // namespace
} // namespace nx

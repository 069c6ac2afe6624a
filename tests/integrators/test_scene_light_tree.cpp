// The scene's light tree (LightSelection::Tree): its choices follow its probabilities over
// hundreds of lights of every bounded kind beside a background, every light that can shine on a
// point keeps a chance there, the tree stays shallow, and a floor lit by one spot among other
// lamps gets the spot's samples (less variance than by power).

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <string>

#include "integrators/lights/light_sampler.h"
#include "integrators/renderer.h"
#include "integrators/scene_reader.h"
#include "support/render_checks.h"
#include "support/statistics.h"

namespace nx {
namespace {

const std::string kSettings =
    "<settings><xres>8</xres><yres>8</yres><mode>spectral_mcpt</mode></settings>"
    "<camera><position>0,0,-30</position><look_at>0,0,0</look_at></camera>";

std::string num(double x) {
  return std::to_string(x);
}

std::string point3(double x, double y, double z) {
  return num(x) + "," + num(y) + "," + num(z);
}

// n lights of each bounded kind in turn (spots aimed every way, point lights, small emitting
// spheres, quads and triangles of random orientation) scattered in a 20-unit box, and a dim
// background: a deterministic scene.
RenderScene manyLights(int n, bool background) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-10, 10), unit(-1, 1), size(0.05, 0.5);
  std::string body;
  for (int i = 0; i < n; ++i) {
    const double x = u(rng), y = u(rng), z = u(rng);
    switch (i % 5) {
    case 0:
      body += "<light type=\"spot\"><position>" + point3(x, y, z) + "</position><look_at>" +
              point3(x + unit(rng), y + unit(rng), z + unit(rng)) + "</look_at><cone_angle>" +
              num(10 + 40 * size(rng)) +
              "</cone_angle><falloff_angle>5</falloff_angle>"
              "<emission>" +
              num(20 * size(rng)) + "</emission></light>";
      break;
    case 1:
      body += "<light><position>" + point3(x, y, z) + "</position><color>1,1,1</color><emission>" +
              num(5 * size(rng)) + "</emission></light>";
      break;
    case 2:
      body += "<sphere><center>" + point3(x, y, z) + "</center><radius>" + num(size(rng)) +
              "</radius><material>matte</material><emission>" + num(3 * size(rng)) +
              "</emission></sphere>";
      break;
    case 3:
      body += "<quad><origin>" + point3(x, y, z) + "</origin><edge_u>" +
              point3(size(rng), unit(rng) * 0.2, 0) + "</edge_u><edge_v>" +
              point3(0, unit(rng) * 0.2, size(rng)) +
              "</edge_v><material>matte</material><emission>" + num(2 * size(rng)) +
              "</emission></quad>";
      break;
    default:
      body += "<triangle><vA>" + point3(x, y, z) + "</vA><vB>" +
              point3(x + size(rng), y + unit(rng) * 0.3, z) + "</vB><vC>" +
              point3(x, y + unit(rng) * 0.3, z + size(rng)) +
              "</vC><material>matte</material><emission>" + num(2 * size(rng)) +
              "</emission></triangle>";
      break;
    }
  }
  return buildRenderScene(parseScene(
      "<scene><settings><xres>8</xres><yres>8</yres><mode>spectral_mcpt</mode>" +
          std::string(background ? "<background>0.01</background>" : "") +
          "</settings><camera><position>0,0,-30</position><look_at>0,0,0</look_at></camera>" +
          body + "</scene>",
      "lights.scn"));
}

// Over 300 lights and a background, at points inside and outside the lights' box with and
// without a receiver normal: probabilities sum to 1, the lights chosen follow them
// (chi-square), and a light that can shine on the point (all but spots turned away) has a
// chance there.
TEST(SceneLightTree, ChoicesFollowProbabilitiesOverManyLights) {
  const RenderScene scene = manyLights(300, true);
  const LightSampler lights(scene, LightSelection::Tree);
  ASSERT_EQ(lights.count(), 301);
  ASSERT_FALSE(lights.tree().empty());
  const Vec3 points[] = {{0.3f, -0.2f, 0.1f}, {4, 9, -7}, {30, 2, 0}};
  const Vec3 normals[] = {Vec3(), normalize(Vec3(0.3f, 1, -0.2f))};
  for (const Vec3& p : points)
    for (const Vec3& n : normals) {
      std::vector<double> expected(301), observed(301, 0);
      double total = 0;
      for (int k = 0; k < lights.count(); ++k) {
        const float pk = lights.probability(k, p, n);
        total += pk;
        expected[static_cast<size_t>(k)] = pk;
        // Every light keeps a chance but a spot whose cone misses p.
        const int own = lights.sceneLightOf(k);
        const SpotLight* spot =
            own >= 0 ? std::get_if<SpotLight>(&scene.lights[static_cast<size_t>(own)]) : nullptr;
        if (!spot || spot->fractionToward(p) > 0) {
          EXPECT_GT(pk, 0.0f) << "light " << k;
        }
      }
      EXPECT_NEAR(total, 1.0, 1e-4);
      const int draws = 200000;
      for (int i = 0; i < draws; ++i) {
        float share = 0, uRest = 0;
        const int k =
            lights.choose(p, n, sampleValue(SamplerKind::Independent, i, 0, 0, 3), share, uRest);
        ASSERT_GE(k, 0);
        EXPECT_NEAR(share, lights.probability(k, p, n), 1e-4f * share + 1e-9f);
        observed[static_cast<size_t>(k)] += 1;
      }
      for (double& e : expected) e *= draws;
      const auto [stat, dof] = test::chiSquare(observed, expected);
      EXPECT_LT(test::chiSquareZ(stat, dof), 4.0) << "chi2 " << stat << " dof " << dof;
    }
}

// A spot aimed away from a point has no chance there; aimed at it, it has (the tree carries
// the cone, a point light's bound would not).
TEST(SceneLightTree, SpotConesPruneTheirClusters) {
  const std::string spots =
      "<light type=\"spot\"><position>0,5,0</position><look_at>0,0,0</look_at>"
      "<cone_angle>20</cone_angle><emission>10</emission></light>"
      "<light type=\"spot\"><position>0.5,5,0</position><look_at>0.5,10,0</look_at>"
      "<cone_angle>20</cone_angle><emission>10</emission></light>"
      "<light type=\"spot\"><position>8,5,0</position><look_at>8,10,0</look_at>"
      "<cone_angle>20</cone_angle><emission>10</emission></light>";
  const RenderScene scene =
      buildRenderScene(parseScene("<scene>" + kSettings + spots + "</scene>", "s.scn"));
  for (LightSelection sel : {LightSelection::Tree, LightSelection::Local}) {
    const LightSampler lights(scene, sel);
    const Vec3 floor(0, 0, 0), up(0, 1, 0);
    EXPECT_GT(lights.probability(0, floor, up), 0.999f);
    EXPECT_LT(lights.probability(1, floor, up), 1e-6f);
    EXPECT_LT(lights.probability(2, floor, up), 1e-6f);
  }
}

// The tree stays about as deep as a balanced one (1024 lights in buckets of at most 8: 7
// levels), also for lights on a line (a row of lamps has no box area to split by).
TEST(SceneLightTree, DepthStaysLogarithmic) {
  const RenderScene scene = manyLights(1024, false);
  const LightSampler lights(scene, LightSelection::Tree);
  EXPECT_EQ(lights.tree().nodeCount() + 1, lights.tree().bucketCount());
  EXPECT_GE(lights.tree().bucketCount(), 1024u / kLightTreeBucket);
  EXPECT_LE(lights.tree().depth(), 16);
  std::string row;
  for (int i = 0; i < 512; ++i)
    row += "<light><position>" + point3(0.1 * i, 3, 0) +
           "</position><color>1,1,1</color><emission>1</emission></light>";
  const RenderScene line =
      buildRenderScene(parseScene("<scene>" + kSettings + row + "</scene>", "row.scn"));
  const LightSampler inLine(line, LightSelection::Tree);
  EXPECT_LE(inLine.tree().depth(), 14);
  // Beyond kMaxLocalLights, the default selection walks the tree.
  EXPECT_EQ(LightSampler(line).selection(), LightSelection::Tree);
  EXPECT_EQ(LightSampler(manyLights(kMaxLocalLights, false)).selection(), LightSelection::Local);
}

// A tree of at most a bucket's lights is one bucket: the exact choice by weight, the same
// probabilities as Local's (here four lights of each kind beside a background).
TEST(SceneLightTree, OneBucketIsTheLocalChoice) {
  const RenderScene scene = manyLights(kLightTreeBucket, true);
  const LightSampler tree(scene, LightSelection::Tree), local(scene, LightSelection::Local);
  EXPECT_EQ(tree.tree().bucketCount(), 1u);
  EXPECT_EQ(tree.tree().depth(), 0);
  for (const Vec3& p : {Vec3(0, 0, 0), Vec3(3, -2, 8)})
    for (int k = 0; k < tree.count(); ++k) {
      const float a = tree.probability(k, p, Vec3(0, 1, 0));
      const float b = local.probability(k, p, Vec3(0, 1, 0));
      EXPECT_NEAR(a, b, 1e-5f * b + 1e-30f) << "light " << k;
    }
}

// Variance of one render's 550 nm band per pixel, from seeds 21 and 22.
double varianceAt550(const RenderScene& scene, LightSelection selection) {
  RenderOptions o;
  o.lightSelection = selection;
  return seedPairVariance(scene, o, 550, 21, 22);
}

// A floor lit by one smooth spot beside three ten times brighter spots aimed sideways (at
// walls out of view): weighed as point lights the sideways spots took most samples, as by
// power; with their cones (local, and the tree: one bucket) the floor's spot gets them all.
// The measured ratio is below 0.01 (docs/performance.md); a quarter leaves room for the two
// renders' own scatter, and the weights of a point light (the code before) give about 1.
TEST(SceneLightTree, ASpotAmongLampsGetsTheSamplesWhereItShines) {
  std::string sideways;
  for (const char* at : {"30,4,0", "-30,4,0", "0,4,30"})
    sideways += "<light type=\"spot\"><position>0,4,0</position><look_at>" + std::string(at) +
                "</look_at><cone_angle>20</cone_angle><color>1,1,1</color><emission>400"
                "</emission></light>";
  const RenderScene scene = buildRenderScene(parseScene(
      "<scene><settings><xres>16</xres><yres>16</yres><mode>spectral_mcpt</mode><depth>1</depth>"
      "<sampl>8</sampl></settings><camera><position>0,3,-0.01</position><look_at>0,0,0</look_at>"
      "<fov>40</fov></camera><plane><normal>0,1,0</normal><distance>0</distance>"
      "<material>matte</material><reflectance>0.5</reflectance></plane>"
      "<light type=\"spot\"><position>0,4,0</position><look_at>0,0,0</look_at>"
      "<cone_angle>25</cone_angle><falloff_angle>10</falloff_angle><color>1,1,1</color>"
      "<emission>40</emission></light>" +
          sideways + "</scene>",
      "spot.scn"));
  const double power = varianceAt550(scene, LightSelection::Power);
  const double local = varianceAt550(scene, LightSelection::Local);
  const double tree = varianceAt550(scene, LightSelection::Tree);
  std::printf("variance at 550 nm: power %.4g, local %.4g, tree %.4g\n", power, local, tree);
  EXPECT_LT(local, 0.25 * power);
  EXPECT_LT(tree, 0.25 * power);
}

} // namespace
} // namespace nx

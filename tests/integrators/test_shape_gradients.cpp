// Derivatives with respect to shape (docs/inverse.md, "Shape and camera"): a sphere's centre
// and radius, forward mode against central differences of renders with common random numbers
// over regions of the image (z-tests on the per-pixel differences, with power), the interior
// term alone inside the sphere's outline, the boundary terms where it moves across the
// background, casts a point light's shadow and an area light's, a closed form for the outline
// term, a test the interior term alone fails, reverse mode against the forward images, and the
// thread count.

#include <gtest/gtest.h>

#include <memory>

#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>

#include <tbb/task_arena.h>

#include "accel/kinds/sphere.h"
#include "core/camera.h"
#include "core/error.h"
#include "integrators/gradients/gradient_setup.h"
#include "integrators/renderer.h"
#include "integrators/scene_params/parameter_numbers.h"
#include "integrators/scene_reader.h"
#include "support/statistics.h"
#include "support/test_scale.h"

namespace nx {
namespace {

constexpr int kSize = 32;

std::string num(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.9g", v);
  return b;
}

// A sphere of material `sphere` at `center` with `radius` (object 1), above a floor of material
// `floor` (object 0, or none when empty), with `extra` (lights) and `settings` (a background).
std::string scene(const Vec3d& center, double radius, const std::string& sphere,
                  const std::string& floor, const std::string& extra, int samples,
                  const std::string& settings) {
  std::string s = "<scene><settings><xres>" + std::to_string(kSize) + "</xres><yres>" +
                  std::to_string(kSize) + "</yres><mode>spectral_mcpt</mode><depth>4</depth>" +
                  "<sampl>" + std::to_string(samples) + "</sampl><bands>400:700:100</bands>" +
                  settings +
                  "</settings><camera><position>0,0.9,-2.6"
                  "</position><look_at>0,0.5,0</look_at><fov>40</fov></camera>";
  if (!floor.empty())
    s += "<plane><normal>0,1,0</normal><distance>0</distance>" + floor + "</plane>";
  else
    s += "<sphere><center>0,-100,0</center><radius>1e-3</radius><material>matte</material>"
         "<reflectance>0.5</reflectance></sphere>"; // keeps the sphere object 1
  s += "<sphere><center>" + num(center.x) + "," + num(center.y) + "," + num(center.z) +
       "</center><radius>" + num(radius) + "</radius>" + sphere + "</sphere>" + extra + "</scene>";
  return s;
}

// The sphere's parameter as differentiated: its scene at a value of component `component`.
struct ShapeCase {
  std::string sphere, floor, extra, settings = "";
  Vec3d center{0, 0.7, 0};
  double radius = 0.5;
  int samples = 256;
  std::string text(const std::string& name, int component, double delta) const {
    Vec3d c = center;
    double r = radius;
    if (name == "objects[1].radius")
      r += delta;
    else
      c = {c.x + (component == 0 ? delta : 0), c.y + (component == 1 ? delta : 0),
           c.z + (component == 2 ? delta : 0)};
    return scene(c, r, sphere, floor, extra, samples, settings);
  }
};

RenderScene built(const std::string& text) {
  return buildRenderScene(parseScene(text, "t.scn"));
}

// Which pixels a comparison sums.
using Region = std::function<bool(int x, int y)>;

// The forward-mode gradient of `name` along a direction (a weighted sum of its slots' images)
// against the central difference of two renders at +-step, summed over a region per band. Over
// kSeeds seeds, each render at the scene's own sample count with its seed (the differences'
// two with the same one): the means of the sums, and the standard error of the mean of their
// difference from the seeds' spread. (Not from the pixels' spread: where an edge moves, the
// difference is + in one pixel and - in the next, so pixels are not independent and their
// spread overstated the error by an order of magnitude, which hid a factor of 2.)
struct Comparison {
  std::vector<double> gradient, difference, standardError;
};

constexpr int kSeeds = 8;

Comparison compareOverSeeds(const std::function<std::string(double)>& text, const std::string& name,
                            const std::vector<std::pair<int, double>>& direction, double step,
                            const Region& region, bool boundary = true) {
  const SceneDesc desc = parseScene(text(0), "t.scn");
  const RenderScene base = buildRenderScene(desc);
  const GradientSetup setup = gradientSetup(desc, {name}, base, true);
  const RenderScene plusScene = built(text(step)), minusScene = built(text(-step));
  std::vector<std::vector<double>> g, f; // [seed][band]
  for (uint32_t seed = 0; seed < kSeeds; ++seed) {
    RenderOptions o;
    o.seed = seed;
    RenderOptions d = o;
    o.gradients = &setup.tangents;
    o.shapeBoundary = boundary;
    const RenderOutput gr = render(base, o);
    const RenderOutput plus = render(plusScene, d), minus = render(minusScene, d);
    const int nb = gr.film.bands().count();
    std::vector<double> gs(static_cast<size_t>(nb), 0.0), fs(static_cast<size_t>(nb), 0.0);
    for (int b = 0; b < nb; ++b)
      for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
          if (!region(x, y)) continue;
          for (const auto& [slot, w] : direction)
            gs[static_cast<size_t>(b)] += w * gr.film.layerMean(x, y, slot, b);
          fs[static_cast<size_t>(b)] +=
              (plus.film.bandMean(x, y, b) - minus.film.bandMean(x, y, b)) / (2 * step);
        }
    g.push_back(gs), f.push_back(fs);
  }
  Comparison out;
  for (size_t b = 0; b < g[0].size(); ++b) {
    test::RunningStats gm, fm, dm;
    for (int k = 0; k < kSeeds; ++k) {
      gm.add(g[static_cast<size_t>(k)][b]);
      fm.add(f[static_cast<size_t>(k)][b]);
      dm.add(g[static_cast<size_t>(k)][b] - f[static_cast<size_t>(k)][b]);
    }
    out.gradient.push_back(gm.mean);
    out.difference.push_back(fm.mean);
    out.standardError.push_back(dm.standardError());
  }
  return out;
}

// The sphere's parameter `name`'s component: c's samples split over the seeds.
Comparison compare(const ShapeCase& c, const std::string& name, int component, double step,
                   const Region& region, bool boundary = true) {
  ShapeCase each = c;
  each.samples = test::scaledSamples(c.samples / kSeeds);
  return compareOverSeeds([&](double h) { return each.text(name, component, h); }, name,
                          {{component, 1.0}}, step, region, boundary);
}

// Agreement within 5 standard errors in every band, and power: the band with the largest
// difference resolved to `power` of it.
void expectAgrees(const Comparison& c, double power, const std::string& what) {
  if (std::getenv("NX_PRINT_COMPARISONS"))
    for (size_t b = 0; b < c.gradient.size(); ++b)
      std::printf("%s band %zu: gradient %.5g difference %.5g se %.3g\n", what.c_str(), b,
                  c.gradient[b], c.difference[b], c.standardError[b]);
  size_t k = 0;
  for (size_t b = 0; b < c.gradient.size(); ++b) {
    EXPECT_LE(std::abs(c.gradient[b] - c.difference[b]), 5 * c.standardError[b])
        << what << " band " << b << ": gradient " << c.gradient[b] << ", difference "
        << c.difference[b] << ", standard error " << c.standardError[b];
    if (std::abs(c.difference[b]) > std::abs(c.difference[k])) k = b;
  }
  EXPECT_LT(c.standardError[k], test::scaledPower(power) * std::abs(c.difference[k]))
      << what << ": no power (" << c.standardError[k] << " against " << c.difference[k] << ")";
}

// True when the pixel's footprint (its corners and centre, widened by `margin` pixels) lies
// wholly inside (inside = true) or wholly outside the sphere's image.
bool footprint(const ShapeCase& c, int x, int y, bool inside, double margin) {
  const RenderScene s = built(c.text("objects[1].radius", 0, 0));
  const SphereShape sphere{c.center, c.radius};
  for (double dy : {-margin, 0.5, 1 + margin})
    for (double dx : {-margin, 0.5, 1 + margin}) {
      const Ray r = s.camera.generateRay(x + dx, y + dy);
      const bool hit = intersectSphere(sphere, Vec3d(r.o), Vec3d(r.d), 0, 1e30).has_value();
      if (hit != inside) return false;
    }
  return true;
}

const std::string kPointLight =
    "<light><position>0.3,3,-2.5</position><color>1,1,1</color><emission scale=\"0.02\">D65"
    "</emission></light>";
const std::string kMatte = "<material>matte</material><reflectance>0.6</reflectance>";
const std::string kFloor = "<material>matte</material><reflectance>0.5</reflectance>";
const std::string kFluorescent =
    "<material>matte</material><reflectance>0.3</reflectance><fluorescence><absorption>460"
    "</absorption><stokes>90</stokes><width>25</width><yield>0.8</yield></fluorescence>";

TEST(ShapeGradients, InteriorInsideTheOutlineMatchesDifferences) {
  // Pixels wholly inside the sphere's image see no outline: the interior term is all there is
  // (hit points sliding on the sphere, its normal turning, the light's direction and distance).
  for (const std::string& material : {kMatte, kFluorescent}) {
    ShapeCase c{material, kFloor, kPointLight};
    c.samples = 512;
    std::vector<bool> inner(kSize * kSize);
    for (int y = 0; y < kSize; ++y)
      for (int x = 0; x < kSize; ++x) inner[y * kSize + x] = footprint(c, x, y, true, 0.5);
    const Region region = [&](int x, int y) { return inner[y * kSize + x]; };
    for (int component = 0; component < 3; ++component)
      expectAgrees(compare(c, "objects[1].center", component, 0.01, region), 0.05,
                   "center[" + std::to_string(component) + "] " + material);
    expectAgrees(compare(c, "objects[1].radius", 0, 0.01, region), 0.05, "radius " + material);
  }
}

// The pixel the sphere's centre is seen in.
std::pair<int, int> imageOfCenter(const ShapeCase& c) {
  const RenderScene s = built(c.text("objects[1].radius", 0, 0));
  const Vec3d toCenter = normalize(c.center - s.camera.position());
  std::pair<int, int> best{0, 0};
  double closest = -2;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x)
      if (const double d = dot(Vec3d(s.camera.generateRay(x + 0.5, y + 0.5).d), toCenter);
          d > closest)
        closest = d, best = {x, y};
  return best;
}

// The sphere's image area in pixels over a region, by the rays through a fine grid of film points
// (an independent geometric computation).
double imageArea(const ShapeCase& c, double radius, const Region& region) {
  const RenderScene s = built(c.text("objects[1].radius", 0, 0));
  const SphereShape sphere{c.center, radius};
  constexpr int kSub = 64;
  double hits = 0;
  for (int y = 0; y < kSize * kSub; ++y)
    for (int x = 0; x < kSize * kSub; ++x) {
      if (!region(x / kSub, y / kSub)) continue;
      const Ray r = s.camera.generateRay((x + 0.5) / kSub, (y + 0.5) / kSub);
      hits += intersectSphere(sphere, Vec3d(r.o), Vec3d(r.d), 0, 1e30).has_value();
    }
  return hits / (kSub * kSub);
}

TEST(ShapeGradients, OutlineAgainstTheBackgroundMatchesDifferencesAndClosedForm) {
  // A black sphere before a uniform background Lb: the image is Lb outside its outline and 0
  // inside, so moving it changes the image through its outline alone (the interior term is 0:
  // nothing of it is differentiated). d(image sum) / d theta = -Lb dA / d theta, A its image
  // area in pixels; the interior term alone gives 0, far from the differences.
  ShapeCase c{"<material>matte</material><reflectance>0</reflectance>", "", "",
              "<background>0.05</background>"};
  c.center = {0.3, 0.6, 0};
  c.samples = 64;
  // (moved sideways, the outline gains on one side what it loses on the other: the half
  // towards which it moves)
  const auto [cx, cy] = imageOfCenter(c);
  const Region all = [](int, int) { return true; };
  const double h = 1e-3;
  for (int component : {-1, 0, 1}) {
    const std::string name = component < 0 ? "objects[1].radius" : "objects[1].center";
    const int k = std::max(component, 0);
    const Region region = component < 0    ? all
                          : component == 0 ? Region([cx = cx](int x, int) { return x > cx; })
                                           : Region([cy = cy](int, int y) { return y < cy; });
    const Comparison moved = compare(c, name, k, 0.01, region);
    expectAgrees(moved, 0.03, name + "[" + std::to_string(k) + "]");
    ShapeCase plus = c, minus = c;
    if (component < 0) {
      plus.radius += h, minus.radius -= h;
    } else {
      plus.center = {c.center.x + (k == 0 ? h : 0), c.center.y + (k == 1 ? h : 0), c.center.z};
      minus.center = {c.center.x - (k == 0 ? h : 0), c.center.y - (k == 1 ? h : 0), c.center.z};
    }
    const double dA =
        (imageArea(plus, plus.radius, region) - imageArea(minus, minus.radius, region)) / (2 * h);
    for (size_t b = 0; b < moved.gradient.size(); ++b)
      EXPECT_NEAR(moved.gradient[b], -0.05 * dA,
                  5 * moved.standardError[b] + 1e-3 * 0.05 * std::abs(dA))
          << name << " band " << b;
    // (the noise of the differences is the comparison's above: the images are the same)
    const Comparison interior = compare(c, name, k, 0.01, region, false);
    for (size_t b = 0; b < interior.gradient.size(); ++b) {
      EXPECT_EQ(interior.gradient[b], 0.0);
      EXPECT_GT(std::abs(interior.difference[b]),
                test::scaledSeparation(10) * moved.standardError[b])
          << name << " band " << b << ": the interior term alone would pass";
    }
  }
}

TEST(ShapeGradients, PointLightShadowOnAFluorescentFloorMatchesDifferences) {
  // A black sphere over a fluorescent floor under a point light: nothing of the sphere is seen
  // but its outline and its shadow's edge, both boundary terms (the shadow's on the film).
  ShapeCase c{"<material>matte</material><reflectance>0</reflectance>", kFluorescent,
              "<light><position>0.8,6,0.3</position><color>1,1,1</color><emission "
              "scale=\"0.05\">D65</emission></light>"};
  c.samples = 256;
  const Region all = [](int, int) { return true; };
  // (sideways, the shadow gains on one side what it loses on the other: the left half)
  expectAgrees(compare(c, "objects[1].center", 0, 0.01, [](int x, int) { return x < kSize / 2; }),
               0.03, "center[0]");
  expectAgrees(compare(c, "objects[1].center", 2, 0.01, all), 0.03, "center[2]");
  expectAgrees(compare(c, "objects[1].radius", 0, 0.01, all), 0.03, "radius");
}

TEST(ShapeGradients, AreaLightShadowAndInterreflectionMatchDifferences) {
  // A small sphere lamp: the sphere's soft shadow and the light it throws on the floor change
  // through the outline of the sphere seen from each floor point (the boundary term of the
  // floor's scattering integral, traced on both sides) and the interior term.
  ShapeCase c{kMatte, kFloor,
              "<sphere><center>0.3,3,-2.5</center><radius>0.1</radius><material>matte</material>"
              "<reflectance>0</reflectance><emission scale=\"0.6\">D65</emission></sphere>"};
  c.samples = 1536;
  std::vector<bool> floor(kSize * kSize);
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) floor[y * kSize + x] = footprint(c, x, y, false, 1.5);
  const Region region = [&](int x, int y) { return floor[y * kSize + x]; };
  // (the outline's term there is sampled where a light is rarely behind it: a weaker power)
  expectAgrees(compare(c, "objects[1].center", 2, 0.03, region), 0.12, "center[2]");
  expectAgrees(compare(c, "objects[1].radius", 0, 0.03, region), 0.2, "radius");
}

TEST(ShapeGradients, ReverseModeIsTheAdjointWeightedForwardSumAndThreadIndependent) {
  ShapeCase c{kMatte, kFloor, kPointLight};
  c.samples = 16;
  const SceneDesc desc = parseScene(c.text("objects[1].radius", 0, 0), "t.scn");
  const RenderScene base = buildRenderScene(desc);
  const GradientSetup setup = gradientSetup(desc, {"objects[1].center"}, base, true);
  RenderOptions forward;
  forward.gradients = &setup.tangents;
  const RenderOutput f = render(base, forward);
  const int nb = f.film.bands().count();
  std::vector<float> adjoint(static_cast<size_t>(kSize * kSize * nb));
  for (size_t i = 0; i < adjoint.size(); ++i) adjoint[i] = static_cast<float>(1 + i % 7);
  RenderOptions reverse = forward;
  reverse.adjoint = &adjoint;
  const RenderOutput r = render(base, reverse);
  ASSERT_EQ(r.gradient.size(), 3u);
  for (int k = 0; k < 3; ++k) {
    double expected = 0, scale = 0;
    for (int y = 0; y < kSize; ++y)
      for (int x = 0; x < kSize; ++x)
        for (int b = 0; b < nb; ++b) {
          const double v =
              adjoint[static_cast<size_t>((y * kSize + x) * nb + b)] * f.film.layerMean(x, y, k, b);
          expected += v, scale += std::abs(v);
        }
    EXPECT_NEAR(r.gradient[static_cast<size_t>(k)], expected, 1e-4 * scale) << k;
  }
  // one thread: the same numbers (the boundary terms are summed in their samples' order)
  std::vector<double> one;
  tbb::task_arena(1).execute([&] { one = render(base, reverse).gradient; });
  EXPECT_EQ(one, r.gradient);
}

// The camera's numbers differentiated in a scene of spheres on a floor under a point light and
// a small sphere lamp: every outline moves on the film (silhouettes, shadows' edges, the
// floor's horizon) and every vertex seen moves.
Comparison compareCamera(const std::string& field, const std::string& value,
                         const std::function<std::string(double)>& moved, double step,
                         int component, int samples, const Region& region) {
  auto text = [&](const std::string& camera) {
    return "<scene><settings><xres>" + std::to_string(kSize) + "</xres><yres>" +
           std::to_string(kSize) + "</yres><mode>spectral_mcpt</mode><depth>4</depth><sampl>" +
           std::to_string(test::scaledSamples(samples / kSeeds)) +
           "</sampl><bands>400:700:100</bands></settings><camera>" + camera +
           "</camera><plane><normal>0,1,0</normal><distance>0</distance>" + kFloor +
           "</plane><sphere><center>0.1,0.7,0</center><radius>0.5</radius>" + kFluorescent +
           "</sphere><sphere><center>0.3,3,-2.5</center><radius>0.1</radius><material>matte"
           "</material><reflectance>0</reflectance><emission scale=\"0.6\">D65</emission>"
           "</sphere>" +
           kPointLight + "</scene>";
  };
  return compareOverSeeds([&](double h) { return text(h == 0 ? value : moved(h)); }, field,
                          {{component, 1.0}}, step, region);
}

TEST(ShapeGradients, CameraTranslatingAndZoomingMatchesDifferences) {
  // (over the whole image what enters on one side leaves on the other: halves of it)
  const Region left = [](int x, int) { return x < kSize / 2; };
  const Region top = [](int, int y) { return y < kSize / 2; };
  const std::string lookAt = "<look_at>0,0.5,0</look_at>";
  auto at = [&](double x, double z, double fov) {
    return "<position>" + num(x) + ",0.9," + num(-2.6 + z) + "</position>" + lookAt + "<fov>" +
           num(40 + fov) + "</fov>";
  };
  expectAgrees(compareCamera(
                   "camera.position", at(0, 0, 0), [&](double h) { return at(h, 0, 0); }, 0.01, 0,
                   512, left),
               0.06, "position[0]");
  expectAgrees(
      compareCamera(
          "camera.position", at(0, 0, 0), [&](double h) { return at(0, h, 0); }, 0.01, 2, 512, top),
      0.05, "position[2]");
  expectAgrees(
      compareCamera(
          "camera.fov", at(0, 0, 0), [&](double h) { return at(0, 0, h); }, 0.05, 0, 512, top),
      0.05, "fov");
}

TEST(ShapeGradients, CameraAmongDisksCylindersAndCapsulesMatchesDifferences) {
  // A fluorescent disk, capped cylinder, open tube and capsule on the floor under a point light
  // and a small sphere lamp: their silhouettes and rims move on the film and as seen from the
  // floor's points (AnalyticPrimitive::outlines), and their shadows' edges.
  const std::string shapes =
      "<disk><center>-0.6,0.4,0.3</center><normal>0.2,0.3,-1</normal><radius>0.25</radius>" +
      kFluorescent +
      "</disk><cylinder><p0>-0.15,0,0.2</p0><p1>-0.15,0.6,0.2</p1><radius>0.15</radius>"
      "<capped>true</capped>" +
      kFluorescent +
      "</cylinder><cylinder><p0>0.3,0.1,0</p0><p1>0.45,0.6,-0.3</p1><radius>0.15</radius>" +
      kFluorescent +
      "</cylinder><capsule><p0>0.7,0.2,0.4</p0><p1>0.8,0.7,0.4</p1><radius>0.15"
      "</radius>" +
      kFluorescent + "</capsule>";
  auto text = [&](double x, double z, int samples) {
    return "<scene><settings><xres>" + std::to_string(kSize) + "</xres><yres>" +
           std::to_string(kSize) + "</yres><mode>spectral_mcpt</mode><depth>4</depth><sampl>" +
           std::to_string(test::scaledSamples(samples / kSeeds)) +
           "</sampl><bands>400:700:100</bands></settings><camera><position>" + num(x) + ",0.9," +
           num(-2.6 + z) +
           "</position><look_at>0,0.5,0</look_at><fov>40</fov></camera><plane><normal>0,1,0"
           "</normal><distance>0</distance>" +
           kFloor + "</plane>" + shapes +
           "<sphere><center>0.3,3,-2.5</center><radius>0.1</radius><material>matte</material>"
           "<reflectance>0</reflectance><emission scale=\"0.6\">D65</emission></sphere>" +
           kPointLight + "</scene>";
  };
  const Region left = [](int x, int) { return x < kSize / 2; };
  const Region top = [](int, int y) { return y < kSize / 2; };
  expectAgrees(compareOverSeeds([&](double h) { return text(h, 0, 512); }, "camera.position",
                                {{0, 1.0}}, 0.01, left),
               0.22, "position[0]");
  expectAgrees(compareOverSeeds([&](double h) { return text(0, h, 512); }, "camera.position",
                                {{2, 1.0}}, 0.01, top),
               0.12, "position[2]");
}

// The camera moving in a scene of meshes: a quad floor (fluorescent), a turned box and a sphere
// on it under a point light, an emitting quad seen behind them. Every mesh's outline moves on
// the film (the box's silhouette and creases, the lamp's border, the floor's far edge), the
// box's shadow's edge moves on the film, and as the camera moves the vertices it sees, the
// meshes' outlines seen from them move too (their boundary after a bounce).
TEST(ShapeGradients, CameraAmongMeshesMatchesDifferences) {
  const Region left = [](int x, int) { return x < kSize / 2; };
  const Region top = [](int, int y) { return y < kSize / 2; };
  auto text = [&](double x, double z, double fov) {
    return "<scene><settings><xres>" + std::to_string(kSize) + "</xres><yres>" +
           std::to_string(kSize) + "</yres><mode>spectral_mcpt</mode><depth>4</depth><sampl>" +
           std::to_string(test::scaledSamples(512 / kSeeds)) +
           "</sampl><bands>400:700:100</bands></settings><camera><position>" + num(x) + ",0.9," +
           num(-2.6 + z) + "</position><look_at>0,0.5,0</look_at><fov>" + num(40 + fov) +
           "</fov></camera><quad><origin>-1.5,0,-1.5</origin><edge_u>3,0,0</edge_u><edge_v>0,0,"
           "2.5</edge_v>" +
           kFluorescent +
           "</quad><box><center>-0.2,0.3,0</center><size>0.6,0.6,0.6</size><transform>"
           "<rotate>0,1,0,35</rotate></transform>" +
           kMatte + "</box><sphere><center>0.55,0.3,-0.3</center><radius>0.3</radius>" + kMatte +
           "</sphere><quad><origin>-0.4,1.1,1.2</origin><edge_u>0.8,0,0</edge_u><edge_v>0,0.4,0"
           "</edge_v><material>matte</material><reflectance>0</reflectance><emission scale="
           "\"0.4\">D65</emission></quad>" +
           kPointLight + "</scene>";
  };
  expectAgrees(compareOverSeeds([&](double h) { return text(h, 0, 0); }, "camera.position",
                                {{0, 1.0}}, 0.01, left),
               0.06, "position[0]");
  expectAgrees(compareOverSeeds([&](double h) { return text(0, h, 0); }, "camera.position",
                                {{2, 1.0}}, 0.01, top),
               0.06, "position[2]");
  expectAgrees(compareOverSeeds([&](double h) { return text(0, 0, h); }, "camera.fov", {{0, 1.0}},
                                0.05, top),
               0.1, "fov");
}

TEST(ShapeGradients, CameraOverASoftShadowMatchesDifferences) {
  // A box, then a sphere, on a fluorescent quad floor under a quad lamp overhead, summed over
  // pixels that see the floor alone: no outline moves there on the film. The soft shadow moves
  // with the camera, and its change at a floor point is the occluder's outline seen from that
  // point moving (the boundary after a bounce), measured against the lamp's held points (the
  // area measure its light is differentiated in): the interior term alone misses it, and
  // against held directions it is 4% off for the sphere, 10% for the box.
  const std::string box = "<box><center>0.1,0.25,0.2</center><size>0.5,0.5,0.5</size><transform>"
                          "<rotate>0,1,0,25</rotate></transform><material>matte</material>"
                          "<reflectance>0</reflectance></box>";
  const std::string sphere = "<sphere><center>0.1,0.3,0.2</center><radius>0.3</radius><material>"
                             "matte</material><reflectance>0</reflectance></sphere>";
  for (const std::string& occluder : {box, sphere}) {
    auto text = [&](double z) {
      return "<scene><settings><xres>" + std::to_string(kSize) + "</xres><yres>" +
             std::to_string(kSize) + "</yres><mode>spectral_mcpt</mode><depth>2</depth><sampl>" +
             std::to_string(test::scaledSamples(512 / kSeeds)) +
             "</sampl><bands>400:700:100</bands></settings><camera><position>0,1.6," + num(-2 + z) +
             "</position><look_at>0,0,0</look_at><fov>40</fov></camera><quad><origin>-3,0,-3"
             "</origin><edge_u>6,0,0</edge_u><edge_v>0,0,6</edge_v>" +
             kFluorescent + "</quad>" + occluder +
             "<quad><origin>-0.4,1.3,-0.2</origin><edge_u>0.7,0,0</edge_u><edge_v>0,0,0.7"
             "</edge_v><material>matte</material><reflectance>0</reflectance><emission scale="
             "\"0.5\">D65</emission></quad></scene>";
    };
    // (3 pixels from the occluder's image and beyond: nearer, floor points see its edges up
    // close, where the uniform choice of an edge leaves heavy tails that 512 samples do not
    // average)
    const RenderScene s = built(text(0));
    const Region floorAlone = [&](int x, int y) {
      for (double dx : {-2.5, -1.5, -0.5, 0.5, 1.5, 2.5, 3.5})
        for (double dy : {-2.5, -1.5, -0.5, 0.5, 1.5, 2.5, 3.5}) {
          const Ray r = s.camera.generateRay(x + dx, y + dy);
          SurfaceHit hit;
          if (!s.geometry->intersect(r, hit) || std::abs(hit.p.y) > 1e-4) return false;
        }
      return true;
    };
    int pixels = 0;
    for (int y = 0; y < kSize; ++y)
      for (int x = 0; x < kSize; ++x) pixels += floorAlone(x, y);
    ASSERT_GT(pixels, kSize * kSize / 3);
    expectAgrees(compareOverSeeds(text, "camera.position", {{2, 1.0}}, 0.01, floorAlone), 0.1,
                 "position[2] over the floor, " + occluder.substr(1, 3));
  }
}

TEST(ShapeGradients, CameraRefusalsSayWhy) {
  const std::string base = scene({0, 0.7, 0}, 0.5, kMatte, kFloor, kPointLight, 4, "");
  auto errorOf = [&](const std::string& text, const std::string& name) {
    const SceneDesc d = parseScene(text, "t.scn");
    try {
      gradientSetup(d, {name}, buildRenderScene(d), true);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  // every primitive's outline is sampled: a disk beside the camera is no longer refused
  std::string disk = base;
  disk.insert(disk.find("</scene>"),
              "<disk><center>0,1,2</center><normal>0,0,-1</normal><radius>0.5</radius>"
              "<material>matte</material><reflectance>0.5</reflectance></disk>");
  EXPECT_EQ(errorOf(disk, "camera.position"), "");
  std::string calibrated = base;
  calibrated.replace(calibrated.find("<fov>40</fov>"), 13,
                     "<intrinsics>30, 30, 16, 16</intrinsics>");
  // (a calibrated camera has no field of view to differentiate: its intrinsics are not yet)
  EXPECT_NE(errorOf(calibrated, "camera.fov").find("no scene parameter named 'camera.fov'"),
            std::string::npos)
      << errorOf(calibrated, "camera.fov");
  EXPECT_EQ(errorOf(base, "camera.up").find("camera.up: not differentiated"), 0u);
}

// An octahedron of rows (object 1) above the floor, flat-shaded: its vertices, moved one by one
// and all together.
const double kOctahedron[6][3] = {{0.55, 0.6, 0}, {-0.45, 0.6, 0},  {0.05, 1.1, 0},
                                  {0.05, 0.1, 0}, {0.05, 0.6, 0.5}, {0.05, 0.6, -0.5}};

// The stage the mesh tests share: the camera, 4 bounces, `samples` spp and the floor's plane
// up to its material (the caller closes it).
std::string stage(int samples) {
  return "<scene><settings><xres>" + std::to_string(kSize) + "</xres><yres>" +
         std::to_string(kSize) + "</yres><mode>spectral_mcpt</mode><depth>4</depth><sampl>" +
         std::to_string(samples) +
         "</sampl><bands>400:700:100</bands></settings><camera><position>0,0.9,-2.6</position>"
         "<look_at>0,0.5,0</look_at><fov>40</fov></camera><plane><normal>0,1,0</normal>"
         "<distance>0</distance>";
}

std::string octahedronScene(const double (&d)[6][3], const std::string& material,
                            const std::string& lights, int samples) {
  std::string vertices;
  for (int i = 0; i < 6; ++i)
    vertices += (i ? ", " : "") + num(kOctahedron[i][0] + d[i][0]) + " " +
                num(kOctahedron[i][1] + d[i][1]) + " " + num(kOctahedron[i][2] + d[i][2]);
  return stage(samples) + kFloor + "</plane><mesh><vertices>" + vertices +
         "</vertices><faces>0 2 4, 2 1 4, 1 3 4, 3 0 4, 2 0 5, 1 2 5, 3 1 5, 0 3 5</faces>" +
         material + "</mesh>" + lights + "</scene>";
}

// The gradient of the vertices' coordinates in `which` (vertex, coordinate, weight: their
// weighted sum, e.g. every vertex's x for a translation) against central differences.
Comparison compareVertices(const std::string& material, const std::string& lights,
                           const std::vector<std::array<int, 2>>& which, int samples,
                           double step = 0.01) {
  auto text = [&](double h) {
    double d[6][3] = {};
    for (const auto& [v, k] : which) d[v][k] = h;
    return octahedronScene(d, material, lights, test::scaledSamples(samples / kSeeds));
  };
  std::vector<std::pair<int, double>> direction;
  for (const auto& [v, k] : which) direction.push_back({3 * v + k, 1.0});
  return compareOverSeeds(text, "objects[1].vertices", direction, step,
                          [](int, int) { return true; });
}

TEST(ShapeGradients, MeshVerticesMatchDifferences) {
  // A black octahedron under a point light: only its outline and its shadow's edge on the
  // fluorescent floor move (boundary terms of its edges on the film); the whole mesh moving
  // (every vertex's coordinate together) and one vertex at its silhouette alone.
  const std::string black = "<material>matte</material><reflectance>0</reflectance>";
  const std::string light = "<light><position>0.8,3,-2.5</position><color>1,1,1</color>"
                            "<emission scale=\"0.05\">D65</emission></light>";
  std::vector<std::array<int, 2>> all;
  for (int v = 0; v < 6; ++v) all.push_back({v, 2});
  expectAgrees(compareVertices(black, light, all, 256), 0.1, "the mesh moving back");
  all.clear();
  for (int v = 0; v < 6; ++v) all.push_back({v, 1});
  expectAgrees(compareVertices(black, light, all, 256), 0.1, "the mesh moving up");
  expectAgrees(compareVertices(black, light, {{0, 0}}, 256), 0.03, "a silhouette vertex");
  // Lit and fluorescent, under a small sphere lamp: its faces turn (the interior term), its
  // edges between faces jump in shading (flat: every edge seen is an outline), and the floor
  // sees more or less of it (the edges seen from each floor point).
  const std::string lamp = "<sphere><center>0.3,3,-2.5</center><radius>0.1</radius><material>"
                           "matte</material><reflectance>0</reflectance><emission scale=\"0.6\">"
                           "D65</emission></sphere>";
  expectAgrees(compareVertices(kFluorescent, lamp, {{2, 1}}, 768), 0.05, "the top vertex");
  expectAgrees(compareVertices(kFluorescent, lamp, {{5, 1}}, 768), 0.07, "the front vertex");
  expectAgrees(compareVertices(kFluorescent, lamp, {{0, 0}}, 768), 0.07, "a silhouette vertex");
}

// The set-up of `name` in `text`: one parameter of `slots` slots shaped `shape`, slot k named
// `slotName`. Returns the scene's description.
SceneDesc expectSlots(const std::string& text, const std::string& name, uint32_t slots,
                      const std::vector<long>& shape, size_t k, const std::string& slotName) {
  const SceneDesc d = parseScene(text, "t.scn");
  const GradientSetup s = gradientSetup(d, {name}, buildRenderScene(d), true);
  EXPECT_EQ(s.parameters.size(), 1u);
  if (s.parameters.size() != 1) return d;
  EXPECT_EQ(s.parameters[0].slots, slots);
  EXPECT_EQ(s.parameters[0].shape, shape);
  EXPECT_EQ(s.tangents.slotNames.at(k), slotName);
  return d;
}

TEST(ShapeGradients, MeshVerticesRefusalsSayWhy) {
  const double none[6][3] = {};
  expectSlots(octahedronScene(none, kMatte, kPointLight, 4), "objects[1].vertices", 18, {6, 3}, 4,
              "objects[1].vertices[1][1]");
}

// The octahedron as an object with a transform p -> m p + t (rows of [m | t], `rows` plus
// `delta` times `direction`), its vertices as rows (flat) or read from an OBJ file with a
// normal per vertex (smooth: the transform turns its shading normals too).
std::string transformedScene(const std::array<double, 12>& rows,
                             const std::array<double, 12>& direction, double delta,
                             const std::string& material, const std::string& lights, int samples,
                             const std::string& objFile) {
  std::string matrix;
  for (int j = 0; j < 12; ++j) matrix += num(rows[j] + delta * direction[j]) + " ";
  matrix += "0 0 0 1";
  std::string mesh;
  if (objFile.empty()) {
    std::string vertices;
    for (int i = 0; i < 6; ++i)
      vertices += (i ? ", " : "") + num(kOctahedron[i][0]) + " " + num(kOctahedron[i][1]) + " " +
                  num(kOctahedron[i][2]);
    mesh = "<mesh><vertices>" + vertices +
           "</vertices><faces>0 2 4, 2 1 4, 1 3 4, 3 0 4, 2 0 5, 1 2 5, 3 1 5, 0 3 5</faces>";
  } else {
    mesh = "<mesh file=\"" + objFile + "\">";
  }
  return stage(samples) + kFloor + "</plane>" + mesh + "<transform><matrix>" + matrix +
         "</matrix></transform>" + material + "</mesh>" + lights + "</scene>";
}

// A sphere of radius 0.35 around the origin as an OBJ file of 12 x 24 quads (two triangles
// each) with a normal per vertex (smooth shading): radial, turned by `turn` radians about x;
// its path.
std::string smoothSphereObj(double turn = 0) {
  const std::string path = ::testing::TempDir() + "/smooth_sphere_" + std::to_string(turn) + ".obj";
  const double cosTurn = std::cos(turn), sinTurn = std::sin(turn);
  std::ofstream f(path);
  const int rings = 12, segments = 24;
  for (int i = 0; i <= rings; ++i)
    for (int j = 0; j < segments; ++j) {
      const double th = kPi * i / rings, ph = 2 * kPi * j / segments;
      const Vec3d n(std::sin(th) * std::cos(ph), std::cos(th), std::sin(th) * std::sin(ph));
      f << "v " << 0.35 * n.x << " " << 0.35 * n.y << " " << 0.35 * n.z << "\n";
      f << "vn " << n.x << " " << cosTurn * n.y - sinTurn * n.z << " "
        << sinTurn * n.y + cosTurn * n.z << "\n";
    }
  auto at = [&](int i, int j) { return i * segments + (j % segments) + 1; };
  for (int i = 0; i < rings; ++i)
    for (int j = 0; j < segments; ++j) {
      const int a = at(i, j), b = at(i, j + 1), c = at(i + 1, j), d = at(i + 1, j + 1);
      if (i > 0)
        f << "f " << a << "//" << a << " " << b << "//" << b << " " << d << "//" << d << "\n";
      if (i + 1 < rings)
        f << "f " << a << "//" << a << " " << d << "//" << d << " " << c << "//" << c << "\n";
    }
  return path;
}

// The gradient of the transform's entries in the direction `direction` (a weighted sum of its
// 12 slots) against the central difference of renders with the transform moved along it, over
// the pixels of `region`.
Comparison compareTransform(const std::array<double, 12>& rows,
                            const std::array<double, 12>& direction, const std::string& material,
                            const std::string& lights, int samples, const std::string& objFile,
                            const Region& region, double step = 0.01) {
  std::vector<std::pair<int, double>> along;
  for (int j = 0; j < 12; ++j)
    if (direction[static_cast<size_t>(j)] != 0)
      along.push_back({j, direction[static_cast<size_t>(j)]});
  return compareOverSeeds(
      [&](double h) {
        return transformedScene(rows, direction, h, material, lights,
                                test::scaledSamples(samples / kSeeds), objFile);
      },
      "objects[1].transform", along, step, region);
}

TEST(ShapeGradients, ObjectTransformMatchesDifferences) {
  // The octahedron scaled by 0.8 about the origin, turned 20 degrees about y and lifted: rows of
  // [m | t]. Directions: a translation, a turn about the z axis (d [m | t] = K [m | t], K the
  // generator), a scale along x and a turn about the z axis through its centre.
  const double c = std::cos(20 * kPi / 180) * 0.8, s = std::sin(20 * kPi / 180) * 0.8;
  const std::array<double, 12> rows{c, 0, s, 0.05, 0, 0.8, 0, 0.15, -s, 0, c, 0};
  const std::array<double, 12> up{0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0};
  // About z through the origin, K = [[0, -1, 0], [1, 0, 0], [0, 0, 0]]: d [m | t] = K [m | t].
  const std::array<double, 12> turn{-rows[4], -rows[5], -rows[6], -rows[7], rows[0], rows[1],
                                    rows[2],  rows[3],  0,        0,        0,       0};
  const std::array<double, 12> scaleX{1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
  const std::string black = "<material>matte</material><reflectance>0</reflectance>";
  const std::string light = "<light><position>0.8,3,-2.5</position><color>1,1,1</color>"
                            "<emission scale=\"0.05\">D65</emission></light>";
  // Black under a point light: its outline and its shadow's edge on the floor.
  const Region all = [](int, int) { return true; };
  const Region left = [](int x, int) { return x < kSize / 2; }; // a turn's changes cancel
  expectAgrees(compareTransform(rows, up, black, light, 256, "", all), 0.06, "lifted");
  expectAgrees(compareTransform(rows, turn, black, light, 512, "", left), 0.05, "turned");
  // Lit and fluorescent under a small sphere lamp: its faces turn and its edges jump (flat), or
  // read from a file with smooth normals that the transform turns with it (tilted about its
  // centre towards the lamp).
  const std::string lamp = "<sphere><center>0.3,3,-2.5</center><radius>0.1</radius><material>"
                           "matte</material><reflectance>0</reflectance><emission scale=\"0.6\">"
                           "D65</emission></sphere>";
  expectAgrees(compareTransform(rows, scaleX, kFluorescent, lamp, 512, "", all), 0.05, "scaled");
  // A smooth sphere mesh read from a file (a normal per vertex) turned about x through its
  // centre (towards the camera and the lamp), seen inside its outline: the surface stays nearly
  // where it was, so the image barely changes; its material points slide, and its shading normals
  // must turn with them by m^-T. A derivative that slid the normals without turning them would be
  // off by the derivative of turning the file's normals alone (differences of renders): the test's
  // power is against that.
  const std::array<double, 12> placed{1, 0, 0, 0.05, 0, 1, 0, 0.6, 0, 0, 1, 0};
  // K = [[0, 0, 0], [0, 0, -1], [0, 1, 0]]: d m = K m (about the centre: t does not move).
  const std::array<double, 12> spin{0,           0, 0,         0,         -placed[8], -placed[9],
                                    -placed[10], 0, placed[4], placed[5], placed[6],  0};
  const ShapeCase inscribed{kFluorescent, kFloor, kPointLight, "", {0.05, 0.6, 0}, 0.33};
  const Region inside = [&](int x, int y) { return footprint(inscribed, x, y, true, 1.0); };
  const Comparison spun =
      compareTransform(placed, spin, kFluorescent, kPointLight, 256, smoothSphereObj(), inside);
  const double h = 0.01;
  auto normalsTurned = [&](double angle) {
    return render(built(transformedScene(placed, spin, 0, kFluorescent, kPointLight,
                                         test::scaledSamples(256), smoothSphereObj(angle))),
                  {});
  };
  const RenderOutput plus = normalsTurned(h), minus = normalsTurned(-h);
  for (size_t b = 0; b < spun.gradient.size(); ++b) {
    EXPECT_LE(std::abs(spun.gradient[b] - spun.difference[b]), 5 * spun.standardError[b])
        << "band " << b;
    double normalsOnly = 0;
    for (int y = 0; y < kSize; ++y)
      for (int x = 0; x < kSize; ++x)
        if (inside(x, y))
          normalsOnly += (plus.film.bandMean(x, y, static_cast<int>(b)) -
                          minus.film.bandMean(x, y, static_cast<int>(b))) /
                         (2 * h);
    if (b == 1) { // the band the dye emits in: the normals' share resolved to 10%
      EXPECT_LT(spun.standardError[b], test::scaledPower(0.1) * std::abs(normalsOnly))
          << "no power against sliding the normals: " << normalsOnly;
    }
  }
}

// A quad (object 1) and a triangle (object 2) standing over the floor under a point light,
// `quad` and `triangle` their corner elements; `material` theirs.
std::string cornersScene(const std::string& quad, const std::string& triangle,
                         const std::string& material, int samples) {
  return stage(samples) + kFluorescent + "</plane><quad>" + quad + material + "</quad><triangle>" +
         triangle + material + "</triangle>" + kPointLight + "</scene>";
}

std::string corners(const char* a, const Vec3d& p, const char* b, const Vec3d& q, const char* c,
                    const Vec3d& r) {
  auto tag = [](const char* t, const Vec3d& v) {
    return std::string("<") + t + ">" + num(v.x) + "," + num(v.y) + "," + num(v.z) + "</" + t + ">";
  };
  return tag(a, p) + tag(b, q) + tag(c, r);
}

TEST(ShapeGradients, QuadAndTriangleCornersMatchDifferences) {
  // A card (quad) and a triangle over a fluorescent floor under a point light: their outlines
  // and their shadows' edges move with their corners; the triangle shares the gathered mesh of
  // inline triangles. Lit matte, so their faces' shading turns with them too.
  const Vec3d origin(-0.7, 0.3, 0.2), edgeU(0.6, 0, -0.1), edgeV(0, 0.6, 0.05);
  const Vec3d a(0.1, 0.2, 0), b(0.7, 0.25, 0.1), c(0.4, 0.9, 0.05);
  auto text = [&](int which, int k, double h) {
    const Vec3d d(k == 0 ? h : 0, k == 1 ? h : 0, k == 2 ? h : 0);
    return cornersScene(corners("origin", origin + (which == 0 ? d : Vec3d()), "edge_u",
                                edgeU + (which == 1 ? d : Vec3d()), "edge_v", edgeV),
                        corners("vA", a, "vB", b, "vC", c + (which == 2 ? d : Vec3d())), kMatte,
                        32);
  };
  const Region all = [](int, int) { return true; };
  const char* names[] = {"objects[1].origin", "objects[1].edge_u", "objects[2].vC"};
  for (int which = 0; which < 3; ++which)
    for (int k : {1, 2}) // (up and back: the image's sum changes; sideways it shifts)
      expectAgrees(compareOverSeeds([&](double h) { return text(which, k, h); }, names[which],
                                    {{k, 1.0}}, 0.01, all),
                   0.1, std::string(names[which]) + "[" + std::to_string(k) + "]");
}

// An analytic primitive other than a sphere (object 1) over the fluorescent floor of the
// shared stage: its element's numbers by parameter, written with one number moved.
struct PrimitiveCase {
  std::string element;
  std::vector<std::pair<std::string, std::vector<double>>> numbers;
  std::string extra; // (e.g. <capped>)
  std::string text(const std::string& name, int k, double h, const std::string& material,
                   const std::string& lights, int samples) const {
    std::string out = stage(samples) + kFluorescent + "</plane><" + element + ">";
    for (const auto& [param, values] : numbers) {
      out += "<" + param + ">";
      for (size_t i = 0; i < values.size(); ++i)
        out += (i ? "," : "") + num(values[i] + (param == name && int(i) == k ? h : 0));
      out += "</" + param + ">";
    }
    return out + extra + material + "</" + element + ">" + lights + "</scene>";
  }
};

// The pixels whose footprint (corners and centre, widened by 1.5 pixels) sees only the floor.
Region floorPixels(const std::string& text) {
  const RenderScene s = built(text);
  auto floor = std::make_shared<std::vector<bool>>(kSize * kSize);
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      bool only = true;
      for (double dy : {-1.5, 0.5, 2.5})
        for (double dx : {-1.5, 0.5, 2.5}) {
          SurfaceHit hit;
          only = only && s.geometry->intersect(s.camera.generateRay(x + dx, y + dy), hit) &&
                 hit.kind == ShapeKind::Plane;
        }
      (*floor)[static_cast<size_t>(y * kSize + x)] = only;
    }
  return [floor](int x, int y) { return (*floor)[static_cast<size_t>(y * kSize + x)]; };
}

// Its parameter `name`'s number k against central differences of renders, over the image or,
// with `floorOnly`, over the floor's pixels away from the primitive's image.
Comparison comparePrimitive(const PrimitiveCase& c, const std::string& name, int k,
                            const std::string& material, const std::string& lights, int samples,
                            double step, bool floorOnly) {
  auto text = [&](double h) {
    return c.text(name, k, h, material, lights, test::scaledSamples(samples / kSeeds));
  };
  const Region all = [](int, int) { return true; };
  return compareOverSeeds(text, "objects[1]." + name, {{k, 1.0}}, step,
                          floorOnly ? floorPixels(text(0)) : all);
}

// Disks, cylinders (capped, and an open tube showing its inside) and capsules: their own
// outlines (silhouettes and rims, AnalyticPrimitive::outlines) and their surfaces' motion
// (AnalyticPrimitive::carry) are all the derivatives ask of them. (a) Black under a point
// light: only their outline and their shadow's edge move (boundary terms on the film). (b) Lit
// matte under a small sphere lamp: the floor's points see their outline move (the boundary
// term of the scattering integral) and the light they throw changes (the interior term), over
// the floor's pixels away from their image, as for spheres (AreaLightShadowAnd...).
TEST(ShapeGradients, DisksCylindersAndCapsulesMatchDifferences) {
  const std::vector<PrimitiveCase> cases = {
      {"disk", {{"center", {0, 0.6, 0}}, {"normal", {0.3, 0.5, -1}}, {"radius", {0.4}}}, ""},
      {"cylinder",
       {{"p0", {-0.35, 0.3, 0}}, {"p1", {0.3, 0.75, 0.2}}, {"radius", {0.22}}},
       "<capped>true</capped>"},
      {"cylinder", {{"p0", {0.05, 0.25, 0.3}}, {"p1", {-0.05, 0.8, -0.1}}, {"radius", {0.3}}}, ""},
      {"capsule", {{"p0", {-0.3, 0.35, 0}}, {"p1", {0.35, 0.6, 0.1}}, {"radius", {0.22}}}, ""},
  };
  // The numbers moved: one of each parameter that changes the image's sum (lit: where the
  // floor's sum changes enough to resolve).
  struct Moved {
    std::string name;
    int k;
    bool lit;
  };
  const std::vector<std::vector<Moved>> moved = {
      {{"center", 1, true}, {"normal", 0, false}, {"radius", 0, true}},
      {{"p1", 0, true}, {"radius", 0, true}},
      {{"p0", 2, true}, {"radius", 0, false}},
      {{"p1", 1, true}, {"p0", 2, true}, {"radius", 0, true}},
  };
  const std::string black = "<material>matte</material><reflectance>0</reflectance>";
  const std::string light = "<light><position>0.8,3,-2.5</position><color>1,1,1</color>"
                            "<emission scale=\"0.05\">D65</emission></light>";
  // (a lamp wide enough that the floor's points often see it behind an outline: the boundary
  // term there is sampled uniformly along the outline, and a small lamp makes it heavy-tailed)
  const std::string lamp = "<sphere><center>0.3,3,-2.5</center><radius>0.5</radius><material>"
                           "matte</material><reflectance>0</reflectance><emission "
                           "scale=\"0.024\">D65</emission></sphere>";
  for (size_t i = 0; i < cases.size(); ++i)
    for (const Moved& m : moved[i]) {
      const std::string what =
          cases[i].element + cases[i].extra + " " + m.name + "[" + std::to_string(m.k) + "]";
      expectAgrees(comparePrimitive(cases[i], m.name, m.k, black, light, 256, 0.01, false), 0.2,
                   what + ", black, point light");
      if (m.lit)
        expectAgrees(comparePrimitive(cases[i], m.name, m.k, kMatte, lamp, 512, 0.01, true), 0.3,
                     what + ", lit, sphere lamp");
    }
}

TEST(ShapeGradients, APrimitivesStepThatMakesNoShapeIsRefused) {
  // A sphere of radius 1e-10: the derivative's step (1e-9) either way would make a negative
  // radius, so the set-up refuses it by name rather than differencing garbage.
  const SceneDesc d =
      parseScene(scene({0, 0.7, 0}, 1e-10, kMatte, kFloor, kPointLight, 4, ""), "t.scn");
  try {
    gradientSetup(d, {"objects[1].radius"}, buildRenderScene(d), true);
    ADD_FAILURE() << "not refused";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "objects[1].radius: cannot differentiate at 1e-10: a step "
                                     "of 1e-09 either way makes no sphere");
  }
}

TEST(ShapeGradients, WarnsOfWhatTheDerivativesMiss) {
  // A sphere lamp over matte spheres and a floor: everything is covered, no warning. A point
  // light with bounces, a glass sphere, a mesh that does not move: one warning each, naming
  // what is missed.
  auto warnings = [](const std::string& text, const std::string& name) {
    const SceneDesc d = parseScene(text, "t.scn");
    return gradientSetup(d, {name}, buildRenderScene(d), true).warnings;
  };
  const std::string lamp = "<sphere><center>0.3,3,-2.5</center><radius>0.1</radius><material>"
                           "matte</material><reflectance>0</reflectance><emission scale=\"0.6\">"
                           "D65</emission></sphere>";
  const std::string covered = scene({0, 0.7, 0}, 0.5, kMatte, kFloor, lamp, 4, "");
  EXPECT_TRUE(warnings(covered, "objects[1].center").empty());
  const auto point =
      warnings(scene({0, 0.7, 0}, 0.5, kMatte, kFloor, kPointLight, 4, ""), "objects[1].radius");
  ASSERT_EQ(point.size(), 1u);
  EXPECT_NE(point[0].find("point and spot lights' shadows"), std::string::npos) << point[0];
  std::string glass = covered;
  glass.insert(glass.find("</scene>"), "<sphere><center>1,0.5,0</center><radius>0.3</radius>"
                                       "<material>glass</material><ior>1.5</ior></sphere>");
  const auto delta = warnings(glass, "objects[1].radius");
  ASSERT_EQ(delta.size(), 1u);
  EXPECT_NE(delta[0].find("mirror reflection or through smooth glass"), std::string::npos)
      << delta[0];
  std::string mesh = covered;
  mesh.insert(mesh.find("</scene>"),
              "<box><center>1,0.5,0</center><size>0.3,0.3,0.3</size>" + kMatte + "</box>");
  const auto still = warnings(mesh, "objects[1].center");
  ASSERT_EQ(still.size(), 1u);
  EXPECT_NE(still[0].find("that do not move"), std::string::npos) << still[0];
  // every analytic primitive's outline is sampled, moving or not: a capsule and an open
  // cylinder that do not move are covered
  std::string tube = covered;
  tube.insert(tube.find("</scene>"), "<capsule><p0>1,0.3,0</p0><p1>1,0.9,0</p1><radius>0.2"
                                     "</radius>" +
                                         kMatte +
                                         "</capsule><cylinder><p0>-1,0.3,0</p0><p1>-1,0.9,0"
                                         "</p1><radius>0.2</radius>" +
                                         kMatte + "</cylinder>");
  EXPECT_TRUE(warnings(tube, "objects[1].center").empty());
  // appearance parameters alone: nothing moves, nothing to warn of
  EXPECT_TRUE(warnings(mesh, "objects[0].reflectance").empty());
}

TEST(ShapeGradients, TransformSlotsAreRowsOfTheAffineMap) {
  // (3, 4) numbers named by row and column, whatever steps the scene wrote; a box's too.
  const std::string text =
      "<scene><settings><xres>8</xres><yres>8</yres><mode>spectral_mcpt</mode><sampl>1</sampl>"
      "</settings><camera><position>0,1,-3</position><look_at>0,0.5,0</look_at><fov>40</fov>"
      "</camera><box><center>0,0.5,0</center><size>1,1,1</size><transform><rotate>0,1,0,30"
      "</rotate><translate>0,0.2,0</translate></transform>" +
      kMatte + "</box>" + kPointLight + "</scene>";
  const SceneDesc d =
      expectSlots(text, "objects[0].transform", 12, {3, 4}, 7, "objects[0].transform[1][3]");
  const ParameterNumbers n = parameterNumbers(d, "objects[0].transform");
  EXPECT_NEAR(n.values[7], 0.2, 1e-12);                      // t.y
  EXPECT_NEAR(n.values[2], std::sin(30 * kPi / 180), 1e-12); // m[0][2]
  // A singular map is refused as the scene's reader refuses it.
  SceneDesc copy = d;
  std::vector<double> flat = n.values;
  for (int c = 0; c < 3; ++c) flat[static_cast<size_t>(4 + c)] = 0;
  EXPECT_FALSE(setParameterNumbers(copy, "objects[0].transform", flat));
}

} // namespace
} // namespace nx

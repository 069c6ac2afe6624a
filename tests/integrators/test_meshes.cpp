// Meshes from files in renders: the same triangles inline and from a PLY render alike, a
// tessellated sphere converges to the analytic one (as a light and as a lit surface).

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>

#include "core/math_util.h"
#include "integrators/lights/light_sampler.h"
#include "integrators/lights/measured_emitter.h"
#include "integrators/renderer.h"
#include "integrators/scene_reader.h"
#include "support/flat_wavelengths.h"
#include "support/icosphere.h"
#include "support/statistics.h"

namespace nx {
namespace {

std::string tempPath(const std::string& name) {
  return ::testing::TempDir() + "/" + name;
}

// Writes a binary little-endian PLY with positions and, if given, normals.
void writePly(const std::string& path, const std::vector<Vec3>& p, const std::vector<Vec3>& n,
              const std::vector<std::array<int, 3>>& faces) {
  std::ofstream f(path, std::ios::binary);
  f << "ply\nformat binary_little_endian 1.0\nelement vertex " << p.size()
    << "\nproperty float x\nproperty float y\nproperty float z\n";
  if (!n.empty()) f << "property float nx\nproperty float ny\nproperty float nz\n";
  f << "element face " << faces.size() << "\nproperty list uchar int vertex_indices\nend_header\n";
  for (size_t i = 0; i < p.size(); ++i) {
    f.write(reinterpret_cast<const char*>(&p[i]), 12);
    if (!n.empty()) f.write(reinterpret_cast<const char*>(&n[i]), 12);
  }
  for (const auto& t : faces) {
    const uint8_t three = 3;
    f.write(reinterpret_cast<const char*>(&three), 1);
    f.write(reinterpret_cast<const char*>(t.data()), 12);
  }
}

// A latitude-longitude sphere of radius r at c with `rings` rings and 2 rings segments, vertices
// on the sphere, outward normals.
void writeSphere(const std::string& path, int rings, double r, const Vec3& c) {
  std::vector<Vec3> p, n;
  std::vector<std::array<int, 3>> faces;
  const int segments = 2 * rings;
  for (int i = 0; i <= rings; ++i)
    for (int j = 0; j <= segments; ++j) {
      const double th = kPi * i / rings, ph = 2 * kPi * j / segments;
      const Vec3 d(static_cast<float>(std::sin(th) * std::cos(ph)),
                   static_cast<float>(std::cos(th)),
                   static_cast<float>(std::sin(th) * std::sin(ph)));
      p.push_back(c + d * static_cast<float>(r));
      n.push_back(d);
    }
  auto at = [&](int i, int j) { return i * (segments + 1) + j; };
  for (int i = 0; i < rings; ++i)
    for (int j = 0; j < segments; ++j) {
      if (i > 0) faces.push_back({at(i, j), at(i, j + 1), at(i + 1, j)});
      if (i + 1 < rings) faces.push_back({at(i, j + 1), at(i + 1, j + 1), at(i + 1, j)});
    }
  writePly(path, p, n, faces);
}

RenderScene sceneOf(const std::string& body) {
  return buildRenderScene(parseScene(
      "<scene><settings><xres>24</xres><yres>16</yres><mode>spectral_mcpt</mode><sampl>16</sampl>"
      "<depth>3</depth></settings><camera><position>0,1.5,-3</position><look_at>0,0.3,0"
      "</look_at><fov>40</fov></camera><plane><normal>0,1,0</normal><distance>0</distance>"
      "<material>matte</material><reflectance>0.5</reflectance></plane>"
      "<light><position>1,3,-1</position><color>4,4,4</color></light>" +
          body + "</scene>",
      tempPath("mesh.scn")));
}

// A "tent" of four triangles: inline, and from a PLY file (moved into place by a <transform>).
// The images agree within their noise, band by band (z-test of the mean difference).
TEST(Meshes, PlyMeshRendersLikeTheSameTrianglesInline) {
  const std::vector<Vec3> p = {
      {-0.5f, 0, -0.5f}, {0.5f, 0, -0.5f}, {0.5f, 0, 0.5f}, {-0.5f, 0, 0.5f}, {0, 0.8f, 0}};
  const std::vector<std::array<int, 3>> f = {{0, 4, 1}, {1, 4, 2}, {2, 4, 3}, {3, 4, 0}};
  // The file holds the tent 10 units down; the transform lifts it back.
  std::vector<Vec3> low = p;
  for (Vec3& v : low) v.y -= 10;
  writePly(tempPath("tent.ply"), low, {}, f);
  std::string inlineText;
  for (const auto& t : f) {
    inlineText += "<triangle>";
    for (int k = 0; k < 3; ++k) {
      const Vec3& v = p[static_cast<size_t>(t[static_cast<size_t>(k)])];
      const char* tag = k == 0 ? "vA" : k == 1 ? "vB" : "vC";
      inlineText += std::string("<") + tag + ">" + std::to_string(v.x) + "," + std::to_string(v.y) +
                    "," + std::to_string(v.z) + "</" + tag + ">";
    }
    inlineText += "<material>matte</material><reflectance>0.8</reflectance></triangle>";
  }
  const RenderScene a = sceneOf(inlineText);
  const RenderScene b = sceneOf("<mesh file=\"tent.ply\"><material>matte</material><reflectance>"
                                "0.8</reflectance><transform><translate>0,10,0</translate>"
                                "</transform></mesh>");
  RenderOptions o;
  o.seed = 1;
  const RenderOutput ra = render(a, o);
  o.seed = 2;
  const RenderOutput rb = render(b, o);
  for (int band = 0; band < ra.film.bands().count(); band += 5) {
    test::RunningStats d;
    for (int y = 0; y < 16; ++y)
      for (int x = 0; x < 24; ++x)
        d.add(ra.film.bandMean(x, y, band) - rb.film.bandMean(x, y, band));
    EXPECT_LT(std::abs(d.mean), 5 * d.standardError() + 1e-9) << band;
  }
  // And pixel by pixel the same surface is seen (depth at the pixel centres).
  int compared = 0;
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 24; ++x) {
      const Ray r = a.camera.generateRay(x + 0.5, y + 0.5);
      SurfaceHit ha, hb;
      ASSERT_EQ(a.geometry->intersect(r, ha), b.geometry->intersect(r, hb));
      if (ha.kind != ShapeKind::Triangle) continue;
      ++compared;
      EXPECT_NEAR(ha.t, hb.t, 1e-5f * ha.t);
    }
  EXPECT_GT(compared, 20);
}

// The irradiance a tessellated emitting sphere of radiance 1 gives a point facing it. Next-event
// estimation (a triangle by area, a point on it by solid angle or by area, a shadow ray) agrees
// with the exact value for the polyhedron (Lambert's formula over its front faces) at each
// tessellation, and that value converges to the analytic sphere's pi (r / d)^2.
TEST(Meshes, TessellatedSphereLightConvergesToTheAnalyticSphere) {
  const Vec3 p(0, 0, -3), n(0, 0, 1);
  const double sphere = kPi / 9;
  const SampledWavelengths w = test::flatWavelengths(550);
  double previous = 1;
  for (int rings : {4, 8, 16, 48}) {
    writeSphere(tempPath("ball.ply"), rings, 1, Vec3(0, 0, 0));
    const RenderScene s = buildRenderScene(parseScene(
        "<scene><settings><xres>4</xres><yres>4</yres><mode>spectral_mcpt</mode></settings>"
        "<camera><position>0,0,-5</position><look_at>0,0,0</look_at></camera>"
        "<mesh file=\"ball.ply\"><material>matte</material><emission>1</emission></mesh></scene>",
        tempPath("ball.scn")));
    // The polyhedron's exact irradiance: its faces that face p.
    const TriangleMesh& mesh = s.geometry->meshes()[0];
    double exact = 0;
    for (size_t t = 0; t < mesh.triangleCount(); ++t) {
      const TriangleShape c = mesh.corners(t);
      // The outward face normal (the sphere is centred at the origin); faces turned towards p.
      Vec3d outward = cross(c.b - c.a, c.c - c.a);
      if (dot(outward, c.a + c.b + c.c) < 0) outward = -outward;
      if (dot(outward, Vec3d(p) - c.a) > 0) exact += projectedSolidAngle(c, Vec3d(p), Vec3d(n));
    }
    for (TriangleLightSampling strategy :
         {TriangleLightSampling::SolidAngle, TriangleLightSampling::Area}) {
      const LightSampler lights(s, LightSelection::Local, strategy);
      test::RunningStats e;
      for (uint32_t i = 0; i < 100000; ++i) {
        LightSample ls;
        double v = 0;
        if (lights.sample(p, sampleValue(SamplerKind::Independent, i, 0, 0, 9),
                          samplePair(SamplerKind::Independent, i, 0, 1, 9), w, ls) &&
            !s.geometry->occluded(shadowRayTo(p, Vec3(0, 0, 0), n, ls)))
          v = ls.radiance[0] * std::max(0.0f, dot(ls.wi, n)) / ls.pdf;
        e.add(v);
        if (i % 211 == 0 && ls.pdf > 0) { // the density pdf() gives the direction it sampled
          Ray r;
          r.o = p;
          r.d = ls.wi;
          SurfaceHit hit;
          if (s.geometry->intersect(r, hit) && hit.prim == ls.prim) {
            EXPECT_NEAR(lights.pdf(p, hit, ls.wi), ls.pdf, 2e-3 * ls.pdf) << rings;
          }
        }
      }
      std::printf("%d rings, %s: NEE %.5f +- %.5f, polyhedron %.5f\n", rings,
                  strategy == TriangleLightSampling::Area ? "by area" : "by solid angle", e.mean,
                  e.standardError(), exact);
      EXPECT_LT(std::abs(e.mean - exact), 4 * e.standardError()) << rings << " " << int(strategy);
      EXPECT_LT(e.standardError(), 0.02 * exact);
    }
    const double err = std::abs(exact / sphere - 1);
    std::printf("%d rings: polyhedron %.5f, sphere %.5f (relative %.5f)\n", rings, exact, sphere,
                err);
    EXPECT_LT(err, previous) << rings;
    previous = err;
  }
  EXPECT_LT(previous, 1e-3); // 48 rings
}

// A matte tessellated sphere with vertex normals, lit by a point light, converges to the image
// of the analytic sphere: the mean absolute difference of the images falls with the resolution.
TEST(Meshes, TessellatedSphereImageConvergesToTheAnalyticSphere) {
  const std::string look = "<material>matte</material><reflectance>0.7</reflectance>";
  const RenderScene analytic =
      sceneOf("<sphere><center>0,0.5,0</center><radius>0.5</radius>" + look + "</sphere>");
  RenderOptions o;
  o.samples = 64;
  o.seed = 5;
  const RenderOutput ref = render(analytic, o);
  double previous = INFINITY;
  for (int rings : {6, 24}) {
    writeSphere(tempPath("ball2.ply"), rings, 0.5, Vec3(0, 0.5f, 0));
    const RenderScene mesh = sceneOf("<mesh file=\"ball2.ply\">" + look + "</mesh>");
    o.seed = 6;
    const RenderOutput out = render(mesh, o);
    double diff = 0;
    for (int y = 0; y < 16; ++y)
      for (int x = 0; x < 24; ++x)
        diff += std::abs(out.film.xyzMean(x, y).y - ref.film.xyzMean(x, y).y);
    diff /= 24 * 16;
    std::printf("%d rings: mean |Y difference| %.5f\n", rings, diff);
    EXPECT_LT(diff, previous);
    previous = diff;
  }
}

// The mesh file `ply` (in the test's temporary folder) as a furnace: reflectance 0.5, emitting
// 1, seen by a camera at the origin.
RenderScene furnaceScene(const std::string& ply) {
  return buildRenderScene(parseScene(
      "<scene><settings><xres>12</xres><yres>12</yres><mode>spectral_mcpt</mode><sampl>32"
      "</sampl><depth>3</depth></settings><camera><position>0,0,0</position><look_at>0,0,1"
      "</look_at></camera><mesh file=\"" +
          ply +
          "\"><material>matte</material><reflectance>0.5</reflectance><emission>1</emission>"
          "</mesh></scene>",
      tempPath("furnace.scn")));
}

// A furnace of reflectance 0.5 emitting 1 seen from inside renders L = 2 in every pixel with
// each strategy (z-test of the image mean, with power: 5 se < 5% of the value).
void expectFurnaceOfTwo(const RenderScene& scene, std::initializer_list<LightSampling> strategies) {
  for (LightSampling s : strategies) {
    RenderOptions o;
    o.lightSampling = s;
    const RenderOutput out = render(scene, o);
    test::RunningStats px;
    for (int y = 0; y < out.film.height(); ++y)
      for (int x = 0; x < out.film.width(); ++x) {
        double v = 0;
        for (int b = 0; b < out.film.bands().count(); ++b) v += out.film.bandMean(x, y, b);
        px.add(v / out.film.bands().count());
      }
    EXPECT_LT(std::abs(px.mean - 2.0), 5 * px.standardError() + 1e-3) << int(s);
    EXPECT_LT(px.standardError(), 0.02) << int(s);
  }
}

// A closed tessellated sphere of reflectance 0.5 emitting 1, seen from inside: a furnace,
// L = Le / (1 - rho) = 2 everywhere, whichever way the mesh light is found (its own triangles
// light each other by next-event estimation, found by BSDF sampling, or both with MIS).
TEST(Meshes, ClosedEmittingMeshIsAFurnace) {
  writeSphere(tempPath("furnace.ply"), 12, 1, Vec3(0, 0, 0));
  expectFurnaceOfTwo(furnaceScene("furnace.ply"),
                     {LightSampling::Mis, LightSampling::NeeOnly, LightSampling::BsdfOnly});
}

// Writes the icosphere of test::icosphereData as a PLY file; `drop` faces from the start are
// left out (an open mesh).
void writeIcosphere(const std::string& path, int levels, double r, const Vec3d& c,
                    size_t drop = 0) {
  test::IcosphereData d = test::icosphereData(levels, r, c);
  d.faces.erase(d.faces.begin(), d.faces.begin() + static_cast<std::ptrdiff_t>(drop));
  writePly(path, d.vertices, {}, d.faces);
}

// Mesh lights through their light trees: a closed icosphere (its back faces never chosen from
// the floor, outside its box; both faces from its own surface) and an open one (a bowl: both
// faces always), over a floor. Next-event estimation alone, BSDF sampling alone, their MIS
// combination and the choice by area (the strategy before the trees) estimate the same image
// (z-test of the mean difference, per-pixel variances). (Directions next-event estimation
// never draws are left to BSDF sampling, whose weight is then 1, so a pruning mistake costs
// noise, not bias: test_mesh_light_tree.cpp checks the pruning itself.)
TEST(Meshes, MeshLightTreesAgreeWithEveryStrategy) {
  writeIcosphere(tempPath("closed_lamp.ply"), 2, 0.3, Vec3d(-0.45, 0.45, 0.1));
  writeIcosphere(tempPath("bowl_lamp.ply"), 2, 0.3, Vec3d(0.45, 0.35, 0.1), 40);
  const RenderScene scene = buildRenderScene(parseScene(
      "<scene><settings><xres>24</xres><yres>16</yres><mode>spectral_mcpt</mode><sampl>32"
      "</sampl><depth>3</depth></settings><camera><position>0,1.2,-2</position><look_at>0,0.2,0"
      "</look_at><fov>45</fov></camera><plane><normal>0,1,0</normal><distance>0</distance>"
      "<material>matte</material><reflectance>0.6</reflectance></plane>"
      "<mesh file=\"closed_lamp.ply\"><material>matte</material><emission>2</emission></mesh>"
      "<mesh file=\"bowl_lamp.ply\"><material>matte</material><emission>A</emission></mesh>"
      "</scene>",
      tempPath("lamps.scn")));
  struct Strategy {
    LightSampling sampling;
    TriangleLightSampling triangles;
  };
  const Strategy strategies[] = {{LightSampling::Mis, TriangleLightSampling::SolidAngle},
                                 {LightSampling::NeeOnly, TriangleLightSampling::SolidAngle},
                                 {LightSampling::BsdfOnly, TriangleLightSampling::SolidAngle},
                                 {LightSampling::Mis, TriangleLightSampling::Area}};
  std::vector<RenderOutput> outs;
  for (size_t i = 0; i < 4; ++i) {
    RenderOptions o;
    o.lightSampling = strategies[i].sampling;
    o.triangleLightSampling = strategies[i].triangles;
    o.seed = 40 + static_cast<uint32_t>(i);
    outs.push_back(render(scene, o));
  }
  for (size_t i = 1; i < 4; ++i) {
    double diff = 0, var = 0, sum = 0;
    for (int y = 0; y < 16; ++y)
      for (int x = 0; x < 24; ++x) {
        diff += outs[i].film.xyzMean(x, y).y - outs[0].film.xyzMean(x, y).y;
        var += outs[i].film.yVariance(x, y) + outs[0].film.yVariance(x, y);
        sum += outs[0].film.xyzMean(x, y).y;
      }
    EXPECT_LT(std::abs(diff), 5 * std::sqrt(var) + 1e-9 * sum) << i;
    EXPECT_LT(std::sqrt(var), 0.01 * sum) << i; // power: 5 se within 5% of the image
  }
}

// The choice among lights with light trees (a closed icosphere, an open bowl) beside a
// rectangle follows the probabilities probability(k, p, n) reports (chi-square over the
// lights), and every light sample's density is the one pdf() gives its direction (receiver
// normal given: the rectangle's and the triangles' cosine warps, the trees' walks), from points
// outside every lamp's box and one inside the closed lamp's box.
TEST(Meshes, LightChoiceAndDensitiesWithLightTrees) {
  writeIcosphere(tempPath("choice_closed.ply"), 2, 0.3, Vec3d(-0.45, 0.45, 0.1));
  writeIcosphere(tempPath("choice_bowl.ply"), 2, 0.3, Vec3d(0.45, 0.35, 0.1), 40);
  const RenderScene scene = buildRenderScene(parseScene(
      "<scene><settings><xres>4</xres><yres>4</yres><mode>spectral_mcpt</mode></settings>"
      "<camera><position>0,1.2,-2</position><look_at>0,0.2,0</look_at></camera>"
      "<mesh file=\"choice_closed.ply\"><material>matte</material><emission>2</emission></mesh>"
      "<mesh file=\"choice_bowl.ply\"><material>matte</material><emission>A</emission></mesh>"
      "<quad><origin>-0.3,1.2,-0.3</origin><edge_u>0.6,0,0</edge_u><edge_v>0,0,0.6</edge_v>"
      "<material>matte</material><emission>3</emission></quad></scene>",
      tempPath("choice.scn")));
  const LightSampler lights(scene);
  ASSERT_EQ(lights.count(), 3);
  const struct {
    Vec3 p, n;
  } points[] = {{Vec3(0.1f, 0, -0.2f), Vec3(0, 1, 0)},
                {Vec3(0.6f, 0.9f, -0.5f), normalize(Vec3(-1, 0.3f, 0.2f))},
                {Vec3(-0.45f, 0.2f, -0.12f), Vec3()}, // inside the closed lamp's box
                {Vec3(0.3f, 0.5f, 0.9f), normalize(Vec3(0.1f, -1, -0.4f))}};
  const SampledWavelengths w = test::flatWavelengths(550);
  for (const auto& [p, n] : points) {
    std::vector<double> expected(3, 0), observed(3, 0);
    double total = 0;
    for (int k = 0; k < 3; ++k)
      total += expected[static_cast<size_t>(k)] = lights.probability(k, p, n);
    EXPECT_NEAR(total, 1.0, 1e-5);
    const int samples = 60000;
    for (double& e : expected) e *= samples;
    int checked = 0;
    for (uint32_t i = 0; i < samples; ++i) {
      const float u = sampleValue(SamplerKind::Independent, i, 0, 0, 4);
      float share = 0, rest = 0;
      const int k = lights.choose(p, n, u, share, rest);
      ASSERT_GE(k, 0);
      EXPECT_NEAR(share, lights.probability(k, p, n), 1e-6);
      observed[static_cast<size_t>(k)] += 1;
      LightSample ls;
      if (i % 7 != 0 ||
          !lights.sample(p, u, samplePair(SamplerKind::Independent, i, 0, 1, 4), w, ls, n))
        continue;
      // The density pdf() gives the direction, where the ray finds the sampled point on its
      // triangle (not a neighbour's edge: the density jumps there).
      Ray r;
      r.o = p;
      r.d = ls.wi;
      SurfaceHit hit;
      if (scene.geometry->intersect(r, hit) && hit.index == ls.shape && hit.prim == ls.prim &&
          std::abs(hit.t - ls.distance) < 1e-4f) {
        EXPECT_NEAR(lights.pdf(p, hit, ls.wi, n), ls.pdf, 2e-3 * ls.pdf) << ls.light;
        ++checked;
      }
    }
    EXPECT_GT(checked, 1000);
    const auto [stat, dof] = test::chiSquare(observed, expected);
    EXPECT_LT(test::chiSquareZ(stat, dof), 4.0) << p.x << " " << p.y;
  }
}

// The closed icosphere furnace: a welded, consistently wound mesh (its light tree knows it is
// closed) seen from inside, where every triangle lights the others from its inner face: L = 2.
TEST(Meshes, ClosedIcosphereFurnace) {
  writeIcosphere(tempPath("ico_furnace.ply"), 2, 1, Vec3d(0, 0, 0));
  expectFurnaceOfTwo(furnaceScene("ico_furnace.ply"), {LightSampling::Mis, LightSampling::NeeOnly});
}

} // namespace
} // namespace nx

// The shape and medium kinds' registries against the scene format, generated from the
// registries (a new kind is covered without editing this file): every kind builds from its
// declared examples into its primitive, needs its required parameters, refuses another kind's
// parameters at their line, and Python-visible names do not collide.

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <fstream>
#include <set>

#include "accel/shape_kinds.h"
#include "core/direction_sampling.h"
#include "core/frame.h"
#include "core/params/material_parameters.h"
#include "core/sampler.h"
#include "integrators/gradients/gradient_setup.h"
#include "integrators/media/medium_kinds.h"
#include "integrators/render_scene.h"
#include "integrators/sampling.h"
#include "integrators/scene_params/parameter_numbers.h"
#include "integrators/scene_reader.h"
#include "io/scene_desc.h"
#include "support/errors.h"
#include "support/render_checks.h"
#include "support/statistics.h"

namespace nx {
namespace {

using test::errorMessage;

std::string withObject(const std::string& object) {
  return sceneText("<xres>4</xres><yres>4</yres><mode>spectral_mcpt</mode>",
                   "<position>0,1,-5</position><look_at>0,0,0</look_at>", object);
}

// A closed tetrahedron in a PLY file, where a file parameter's example names a mesh.
std::string exampleMesh() {
  const std::string path = ::testing::TempDir() + "/shape_kind_tetrahedron.ply";
  std::ofstream f(path);
  f << "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
       "property float z\nelement face 4\nproperty list uchar int vertex_indices\nend_header\n"
       "0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
  return path;
}

// Whether `name` is among a parameter's excludes.
bool excludes(const ShapeParameter& p, const std::string& name) {
  bool found = false;
  forEachWord(p.spec.excludes, [&](const std::string& w) { found = found || w == name; });
  return found;
}

// The parameters of one example: each in order unless one chosen before excludes it; the
// alternative form leaves out those that exclude others (a mesh's rows instead of its file).
std::vector<const ShapeParameter*> exampleParameters(const ShapeKindSpec& kind, bool alternative) {
  std::vector<const ShapeParameter*> chosen;
  for (const ShapeParameter& p : kind.params()) {
    if (alternative && *p.spec.excludes && p.attribute) continue;
    bool excluded = false;
    for (const ShapeParameter* c : chosen) excluded = excluded || excludes(*c, p.spec.name);
    if (!excluded) chosen.push_back(&p);
  }
  return chosen;
}

// Whether the kind has a second form (parameters that exclude others).
bool hasAlternative(const ShapeKindSpec& kind) {
  return exampleParameters(kind, true).size() != exampleParameters(kind, false).size();
}

// The kind's element with its example's parameters at their declared examples, and `extra`
// inside.
std::string exampleObject(const ShapeKindSpec& kind, const std::string& extra = "",
                          bool alternative = false) {
  std::string attributes, children;
  for (const ShapeParameter* p : exampleParameters(kind, alternative)) {
    const std::string value = p->spec.type == ParamType::File ? exampleMesh() : p->spec.example;
    if (p->attribute)
      attributes += " " + std::string(p->spec.name) + "=\"" + value + "\"";
    else
      children += "<" + std::string(p->spec.name) + ">" + value + "</" + p->spec.name + ">";
  }
  return "<" + std::string(kind.name) + attributes + ">" + children + extra +
         "<material>matte</material><reflectance>0.5</reflectance></" + kind.name + ">";
}

TEST(ShapeKinds, EveryKindBuildsFromItsExamplesIntoOnePrimitive) {
  std::set<std::string> names;
  for (const ShapeKindSpec& kind : shapeKinds()) {
    SCOPED_TRACE(kind.name);
    EXPECT_TRUE(names.insert(kind.name).second);
    EXPECT_EQ(findShapeKind(kind.name), &kind);
    for (bool alternative : {false, true}) {
      if (alternative && !hasAlternative(kind)) continue;
      SCOPED_TRACE(alternative ? "alternative form" : "first form");
      const SceneDesc d = parseScene(withObject(exampleObject(kind, "", alternative)), "t.scn");
      ASSERT_EQ(d.objects.size(), 1u);
      EXPECT_EQ(d.objects[0].shape, kind.name);
      for (const ShapeParameter* p : exampleParameters(kind, alternative))
        EXPECT_TRUE(d.objects[0].geometry.has(p->spec.name));
      const RenderScene s = buildRenderScene(d);
      size_t appearances = s.meshes.size(), shapes = 0;
      for (const auto& a : s.shapeAppearances) appearances += a.size();
      forEachAnalyticKind([&]<class P>() { shapes += s.geometry->primitives<P>().size(); });
      EXPECT_EQ(appearances, 1u);
      EXPECT_EQ(shapes + s.geometry->planes().size() + s.geometry->meshes().size(), 1u);
    }
  }
}

// The ball around a geometry's bounded shapes: its centre and radius.
std::pair<Vec3d, double> boundingBall(const GeometryScene& g) {
  const BoundingBox box = g.bounds();
  return {(Vec3d(box.lo) + Vec3d(box.hi)) * 0.5,
          1.01 * length(Vec3d(box.hi) - Vec3d(box.lo)) * 0.5};
}

// Isotropic uniform random lines through the geometry's bounding ball (a direction uniform on
// the sphere, a point uniform on the disk across it): calls line(crossings, points) with every
// crossing of the geometry along each line and the points where they are.
template <class Line>
void forEachLine(const GeometryScene& g, uint32_t lines, Line&& line) {
  const auto [centre, radius] = boundingBall(g);
  std::vector<Vec3d> points;
  for (uint32_t i = 0; i < lines; ++i) {
    auto u = [&](uint32_t dim) {
      return static_cast<double>(sampleValue(SamplerKind::Independent, i, 0, dim, 7));
    };
    const double z = 1 - 2 * u(0), phi = 2 * kPi * u(1);
    const double rz = std::sqrt(std::max(0.0, 1 - z * z));
    const Vec3d d(rz * std::cos(phi), rz * std::sin(phi), z);
    const AxisFrame f = AxisFrame::of(d);
    const double r = radius * std::sqrt(u(2)), psi = 2 * kPi * u(3);
    const Vec3d o =
        centre + f.s * (r * std::cos(psi)) + f.t * (r * std::sin(psi)) - d * (2 * radius);
    Ray ray{Vec3(o), Vec3(d), 0.0f, static_cast<float>(4 * radius)};
    points.clear();
    SurfaceHit hit;
    while (points.size() < 64 && g.intersect(ray, hit)) {
      points.push_back(Vec3d(hit.p));
      ray.tMin = hit.t + static_cast<float>(1e-5 * radius);
    }
    line(static_cast<int>(points.size()), points);
  }
}

// The area of every bounded primitive of a geometry (planes are infinite: not counted).
double boundedArea(const GeometryScene& g) {
  double area = 0;
  forEachAnalyticKind([&]<class P>() {
    for (const P& p : g.primitives<P>()) area += p.area();
  });
  for (const TriangleMesh& m : g.meshes()) area += m.area();
  return area;
}

// Cauchy-Crofton: isotropic uniform random lines through a ball of radius R cross a surface
// inside it 2 A / (4 pi R^2) times on average (the ball's own surface: twice). Every kind at
// its declared example: the crossings its intersection finds agree with the area its primitive
// declares, within 4.5 standard errors; so intersection and area are checked against each
// other, independently of how either is written. Planes are infinite (no area): the one kind
// left out, by name.
TEST(ShapeKinds, EveryBoundedKindsAreaMatchesItsCrossingsByCrofton) {
  constexpr uint32_t kLines = 200000;
  std::set<std::string> unbounded;
  for (const ShapeKindSpec& kind : shapeKinds()) {
    SCOPED_TRACE(kind.name);
    const RenderScene s = buildRenderScene(parseScene(withObject(exampleObject(kind)), "t.scn"));
    const GeometryScene& g = *s.geometry;
    if (!g.planes().empty()) {
      unbounded.insert(kind.name);
      continue;
    }
    const double area = boundedArea(g);
    ASSERT_GT(area, 0);
    const double radius = boundingBall(g).second;
    test::RunningStats crossings;
    forEachLine(g, kLines, [&](int count, const std::vector<Vec3d>&) { crossings.add(count); });
    const double expected = 2 * area / (4 * kPi * radius * radius);
    EXPECT_NEAR(crossings.mean, expected, 4.5 * crossings.standardError())
        << "declared area " << area << ", crossings per line " << crossings.mean << " +- "
        << crossings.standardError() << ", expected " << expected;
  }
  EXPECT_EQ(unbounded, std::set<std::string>{"plane"});
}

// The moments a sample of surface points is compared by: x, y, z and their products.
std::array<double, 9> moments(const Vec3d& p) {
  return {p.x, p.y, p.z, p.x * p.x, p.y * p.y, p.z * p.z, p.x * p.y, p.y * p.z, p.z * p.x};
}

// A primitive's area sampling (`sampleArea`, what emitting analytic primitives are sampled by)
// draws points uniformly by area: the crossing points of isotropic random lines are uniform by
// area too (Cauchy-Crofton), so the two samples' means of x, y, z and their products agree
// (two-sample z-tests, 4.5 standard errors); every drawn point lies on the surface (a ray back
// along its normal meets it there). Generated: every kind whose primitive has sampleArea, at
// its declared example.
TEST(ShapeKinds, EveryAreaSampledPrimitiveDrawsPointsUniformlyByArea) {
  constexpr uint32_t kSamples = 200000;
  int checked = 0;
  for (const ShapeKindSpec& kind : shapeKinds()) {
    SCOPED_TRACE(kind.name);
    const RenderScene s = buildRenderScene(parseScene(withObject(exampleObject(kind)), "t.scn"));
    const GeometryScene& g = *s.geometry;
    const double size = boundingBall(g).second;
    auto check = [&](const auto& primitives) {
      for (const auto& primitive : primitives) {
        if constexpr (requires { primitive.sampleArea(Sample2{}); }) {
          ++checked;
          std::array<test::RunningStats, 9> drawn, crossed;
          for (uint32_t i = 0; i < kSamples; ++i) {
            const AreaSample a =
                primitive.sampleArea(samplePair(SamplerKind::Independent, i, 0, 0, 13));
            const std::array<double, 9> m = moments(a.p);
            for (size_t k = 0; k < m.size(); ++k) drawn[k].add(m[k]);
            if (i % 64 == 0) { // on the surface: a ray back along the normal meets it at p
              const double back = 1e-3 * size;
              Ray ray{Vec3(a.p + a.n * back), Vec3(a.n * -1.0), 0.0f, static_cast<float>(2 * back)};
              SurfaceHit hit;
              ASSERT_TRUE(g.intersect(ray, hit)) << "a drawn point off the surface";
              EXPECT_LT(length(Vec3d(hit.p) - a.p), 1e-5 * size);
            }
          }
          forEachLine(g, kSamples, [&](int, const std::vector<Vec3d>& points) {
            for (const Vec3d& p : points) {
              const std::array<double, 9> m = moments(p);
              for (size_t k = 0; k < m.size(); ++k) crossed[k].add(m[k]);
            }
          });
          for (size_t k = 0; k < drawn.size(); ++k) {
            const double se = std::hypot(drawn[k].standardError(), crossed[k].standardError());
            EXPECT_LT(std::abs(drawn[k].mean - crossed[k].mean), 4.5 * se + 1e-9 * size * size)
                << "moment " << k << ": drawn " << drawn[k].mean << ", crossings "
                << crossed[k].mean << " +- " << se;
          }
        }
      }
    };
    check(g.meshes());
    forEachAnalyticKind([&]<class P>() { check(g.primitives<P>()); });
  }
  EXPECT_GE(checked, static_cast<int>(std::tuple_size_v<AnalyticShapes>))
      << "every analytic primitive samples by area";
}

// The flux that leaves a uniform emitter per unit radiance, by Monte Carlo: a point uniformly
// by area, a face at random, a cosine-weighted direction; what leaves is what meets nothing
// (the scene holds only the shape): 2 pi A times the fraction that escapes. Every analytic
// primitive, at every kind's declared example, agrees with its fluxPerRadiance (what
// quantity="flux" divides by) within 4.5 standard errors; an open tube (the cylinder's
// example is capped) too, whose inside's light partly leaves through its ends.
TEST(ShapeKinds, EveryPrimitivesFluxPerRadianceIsWhatLeavesIt) {
  constexpr uint32_t kSamples = 200000;
  std::vector<std::string> objects;
  for (const ShapeKindSpec& kind : shapeKinds()) objects.push_back(exampleObject(kind));
  objects.push_back("<cylinder><p0>0,0,0</p0><p1>0.3,1.1,0.2</p1><radius>0.35</radius>"
                    "<material>matte</material><reflectance>0.5</reflectance></cylinder>");
  int checked = 0;
  for (const std::string& object : objects) {
    SCOPED_TRACE(object);
    const RenderScene s = buildRenderScene(parseScene(withObject(object), "t.scn"));
    const GeometryScene& g = *s.geometry;
    const double size = boundingBall(g).second;
    forEachAnalyticKind([&]<class P>() {
      for (const P& shape : g.primitives<P>()) {
        ++checked;
        test::RunningStats escapes;
        for (uint32_t i = 0; i < kSamples; ++i) {
          const AreaSample a = shape.sampleArea(samplePair(SamplerKind::Independent, i, 0, 0, 5));
          const Sample2 u = samplePair(SamplerKind::Independent, i, 0, 1, 5);
          const double face = u.u < 0.5 ? 1.0 : -1.0;
          const Sample2 w{u.u < 0.5 ? 2 * u.u : 2 * u.u - 1, u.v};
          const Vec3d n = a.n * face;
          const Vec3d d(Frame::fromNormal(Vec3(n)).toWorld(sampleCosineHemisphere(w)));
          Ray ray{Vec3(a.p + n * (1e-6 * size)), Vec3(d), 0.0f, INFINITY};
          SurfaceHit hit;
          escapes.add(g.intersect(ray, hit) ? 0.0 : 1.0);
        }
        const double scale = 2 * kPi * shape.area();
        EXPECT_NEAR(shape.fluxPerRadiance(), scale * escapes.mean,
                    4.5 * scale * escapes.standardError() + 1e-9 * scale)
            << primitiveName(kShapeKindOf<P>);
      }
    });
  }
  EXPECT_GE(checked, static_cast<int>(std::tuple_size_v<AnalyticShapes>) + 1);
}

// Calls check(primitive) for every analytic primitive of every shape kind's declared example
// (under a trace naming the kind); returns how many it checked.
template <class Check>
int forEachExamplePrimitive(Check&& check) {
  int checked = 0;
  for (const ShapeKindSpec& kind : shapeKinds()) {
    SCOPED_TRACE(kind.name);
    const RenderScene s = buildRenderScene(parseScene(withObject(exampleObject(kind)), "t.scn"));
    forEachAnalyticKind([&]<class P>() {
      for (const P& shape : s.geometry->primitives<P>()) {
        check(shape);
        ++checked;
      }
    });
  }
  return checked;
}

// uv is a chart of the surface with dp/du its tangent: at points drawn on a primitive, the
// hit of a short ray back along the normal, and the hit the same way a small step along its
// dp/du away, differ by that step in u and not at all in v (to first order: steps of 1e-3,
// compared to 5%). Every analytic primitive at every kind's declared example; points near a
// seam of u or a pole are left out.
TEST(ShapeKinds, EveryPrimitivesUvIsAChartWithDpduItsTangent) {
  const int checked = forEachExamplePrimitive([&]<class P>(const P& shape) {
    const double size = std::sqrt(shape.area());
    // the surface where a short ray back along n from near x meets it
    auto hitAt = [&](const Vec3d& x, const Vec3d& n, SurfaceHit& h) {
      const Vec3d o = x + n * (1e-3 * size), d = n * -1.0;
      const auto found = shape.intersect(o, d, 0, 2e-3 * size);
      if (!found) return false;
      h.t = static_cast<float>(found->t);
      h.prim = found->part;
      h.kind = kShapeKindOf<P>;
      shape.fillHit(o, d, found->t, found->part, h);
      surfaceUv(h);
      return true;
    };
    int compared = 0;
    for (uint32_t i = 0; i < 2000; ++i) {
      const AreaSample x = shape.sampleArea(samplePair(SamplerKind::Independent, i, 0, 0, 9));
      SurfaceHit a, b;
      if (!hitAt(x.p, x.n, a)) continue;
      if (a.u < 0.01 || a.u > 0.99 || a.v < 0.02 || a.v > 0.98) continue; // seam, poles
      const double du = 1e-3;
      if (!hitAt(Vec3d(a.p) + Vec3d(a.dpdu) * du, x.n, b) || b.prim != a.prim) continue;
      EXPECT_NEAR(b.u - a.u, du, 0.05 * du) << "at u " << a.u << " v " << a.v;
      EXPECT_NEAR(b.v - a.v, 0.0, 0.05 * du) << "at u " << a.u << " v " << a.v;
      ++compared;
    }
    EXPECT_GT(compared, 1000) << primitiveName(kShapeKindOf<P>);
  });
  EXPECT_GE(checked, static_cast<int>(std::tuple_size_v<AnalyticShapes>));
}

// What a ray from o along d first meets of a primitive: nothing, or its part, distance and
// normal (for telling whether two nearby rays see the same surface).
template <class P>
struct FirstSeen {
  bool hit = false;
  uint32_t part = 0;
  double t = 0;
  Vec3d n;
  double cosine = 0; // |n . d|
  FirstSeen(const P& shape, const Vec3d& o, const Vec3d& d) {
    const auto h = shape.intersect(o, d, 1e-9, 1e30);
    if (!h) return;
    SurfaceHit s;
    shape.fillHit(o, d, h->t, h->part, s);
    hit = true, part = h->part, t = h->t, n = Vec3d(s.ng), cosine = std::abs(dot(n, d));
  }
  // The same surface as b, seen by a ray `angle` radians away: both miss, or both meet it
  // with nearly the same normal at distances no further apart than a surface continuous
  // between them allows (the parts may differ where the surface goes on smoothly: a capsule's
  // tube into its ends).
  bool same(const FirstSeen& b, double size, double angle) const {
    if (hit != b.hit) return false;
    if (!hit) return true;
    const double slope = std::min(cosine, b.cosine);
    return dot(n, b.n) > 0.98 &&
           std::abs(t - b.t) < 0.02 * size + 5 * t * angle / std::max(slope, 1e-3);
  }
};

// The outline a primitive gives (AnalyticPrimitive::outlines) is where what a point sees of
// it jumps, and the only place: from viewpoints around every analytic primitive at every
// kind's declared example, (a) two rays either side of each of its points (1e-3 of the
// distance apart across it) see different surfaces, unless the primitive itself hides the
// point; (b) wherever two rays 2e-3 radians apart see different surfaces, an outline point
// lies within 4e-3 radians of them. A missing rim or silhouette fails (b), a wrong one (a).
TEST(ShapeKinds, EveryPrimitivesOutlineIsWhereWhatAPointSeesOfItJumps) {
  const int checked = forEachExamplePrimitive([&]<class P>(const P& shape) {
    const BoundingBox box = shape.bounds();
    const Vec3d center = (box.lo + box.hi) * 0.5;
    const double size = length(box.hi - box.lo);
    int jumps = 0, crossings = 0;
    for (uint32_t view = 0; view < 6; ++view) {
      const Vec3d dir(sampleUniformSphere(samplePair(SamplerKind::Independent, view, 0, 0, 3)));
      const Vec3d o = center + dir * (size * (1.2 + 0.3 * view));
      OutlineCurves curves;
      shape.outlines(o, curves);
      ASSERT_GT(curves.count, 0) << "seen from " << o.x << ", " << o.y << ", " << o.z;
      std::vector<Vec3d> points; // the outline densely, as unit directions from o
      for (int c = 0; c < curves.count; ++c) {
        const OutlineCurve& curve = curves.curve[static_cast<size_t>(c)];
        for (int i = 0; i < 4096; ++i) {
          const Vec3d m = curve.at((i + 0.5) / 4096);
          if (curve.keeps(m)) points.push_back(normalize(m - o));
        }
        // (a) either side of its points
        for (int i = 0; i < 64; ++i) {
          const double u = (i + 0.37) / 64;
          const Vec3d m = curve.at(u);
          if (!curve.keeps(m)) continue;
          const Vec3d ne = normalize(cross(m - o, curve.tangent(u)));
          const double dist = length(m - o);
          const FirstSeen<P> toward(shape, o, normalize(m - o));
          if (toward.hit && toward.t < dist * (1 - 1e-6)) continue; // hidden by itself
          const FirstSeen<P> a(shape, o, normalize(m - ne * (1e-3 * dist) - o));
          const FirstSeen<P> b(shape, o, normalize(m + ne * (1e-3 * dist) - o));
          EXPECT_FALSE(a.same(b, size, 2e-3)) << "curve " << c << " at " << u;
          ++jumps;
        }
      }
      // (b) pairs of rays that see different surfaces lie near the outline
      for (uint32_t i = 0; i < 4000; ++i) {
        const Sample2 r1 = samplePair(SamplerKind::Independent, i, view, 0, 5);
        const Sample2 r2 = samplePair(SamplerKind::Independent, i, view, 1, 5);
        const Vec3d target =
            box.lo + Vec3d((box.hi.x - box.lo.x) * r1.u, (box.hi.y - box.lo.y) * r1.v,
                           (box.hi.z - box.lo.z) * r2.u);
        const Vec3d d1 = normalize(target - o);
        const Frame f = Frame::fromNormal(Vec3(d1));
        const double phi = 2 * kPi * r2.v;
        const Vec3d d2 =
            normalize(d1 + (Vec3d(f.s) * std::cos(phi) + Vec3d(f.t) * std::sin(phi)) * 2e-3);
        if (FirstSeen<P>(shape, o, d1).same(FirstSeen<P>(shape, o, d2), size, 2e-3)) continue;
        double nearest = 1e30;
        for (const Vec3d& w : points) nearest = std::min(nearest, length(w - d1));
        EXPECT_LT(nearest, 4e-3) << "a jump no outline explains, view " << view;
        ++crossings;
      }
    }
    EXPECT_GT(jumps, 100) << primitiveName(kShapeKindOf<P>);
    EXPECT_GT(crossings, 50) << primitiveName(kShapeKindOf<P>);
  });
  EXPECT_GE(checked, static_cast<int>(std::tuple_size_v<AnalyticShapes>));
}

// How a primitive's parameters move its surface (AnalyticPrimitive::carry, differenced by the
// gradient set-up: PrimitiveMotion): for every parameter a kind declares differentiable, at
// every analytic kind's declared example, each number moved by h = 1e-3 moves the surface
// through x + h v (within h^2: 1e-5, where a velocity wrong to first order is off by ~1e-3),
// its normal there to n + h dn (within 1e-4), v and dn from the set-up's motion at x.
TEST(ShapeKinds, EveryDifferentiableParameterMovesThePrimitiveAsItsMotionSays) {
  int checked = 0;
  for (const ShapeKindSpec& kind : shapeKinds()) {
    SCOPED_TRACE(kind.name);
    const SceneDesc desc = parseScene(withObject(exampleObject(kind)), "t.scn");
    const RenderScene base = buildRenderScene(desc);
    forEachAnalyticKind([&]<class P>() {
      if (base.geometry->primitives<P>().empty()) return;
      const P& shape = base.geometry->primitives<P>()[0];
      for (const ShapeParameter& sp : kind.params()) {
        if (!sp.spec.differentiable || !desc.objects[0].geometry.find(sp.spec.name)) continue;
        const std::string name = "objects[0]." + std::string(sp.spec.name);
        SCOPED_TRACE(name);
        const GradientSetup setup = gradientSetup(desc, {name}, base, true);
        const auto& motions = setup.tangents.shapes.motions<P>().at(0);
        const ParameterNumbers n = parameterNumbers(desc, name);
        ASSERT_EQ(motions.size(), n.values.size());
        for (size_t j = 0; j < n.values.size(); ++j) {
          const double h = 1e-3;
          SceneDesc moved = desc;
          std::vector<double> values = n.values;
          values[j] += h;
          ASSERT_TRUE(setParameterNumbers(moved, name, values));
          const P& after = buildRenderScene(moved).geometry->primitives<P>()[0];
          int compared = 0;
          for (uint32_t i = 0; i < 400; ++i) {
            const AreaSample x =
                shape.sampleArea(samplePair(SamplerKind::Independent, i, 0, 0, 11));
            Vec3d v, dn;
            motions[j].at(shape, x.p, x.part, v, dn);
            // the moved surface where a short ray along the moved normal through x + h v
            // meets it
            const Vec3d y = x.p + v * h, ny = normalize(x.n + dn * h);
            const auto found = after.intersect(y + ny * 1e-2, ny * -1.0, 0, 2e-2);
            if (!found) continue;
            SurfaceHit hit;
            after.fillHit(y + ny * 1e-2, ny * -1.0, found->t, found->part, hit);
            EXPECT_NEAR(found->t, 1e-2, 1e-5) << "the point at u " << i;
            EXPECT_LT(length(Vec3d(hit.ng) - ny), 1e-4) << "the normal at u " << i;
            ++compared;
          }
          EXPECT_GT(compared, 300);
          ++checked;
        }
      }
    });
  }
  // a sphere's centre and radius, a disk's centre, normal and radius, a cylinder's and a
  // capsule's ends and radius: 4 + 7 + 7 + 7 numbers
  EXPECT_GE(checked, 25);
}

// Normals of any non-zero length, as the declarations say: 1e-300 (whose square underflows to
// 0) and 1e12 make unit normals; only zero is refused.
TEST(ShapeKinds, NormalsOfAnyNonZeroLengthAreTaken) {
  for (const char* n : {"0,1e-300,0", "0,-1e12,0", "1e-300,1e-300,0"}) {
    SCOPED_TRACE(n);
    const RenderScene s = buildRenderScene(parseScene(
        withObject(
            "<disk><center>0,0,0</center><normal>" + std::string(n) +
            "</normal><radius>1</radius><material>matte</material><reflectance>0.5</reflectance>"
            "</disk><plane><normal>" +
            n +
            "</normal><distance>0</distance><material>matte</material><reflectance>0.5"
            "</reflectance></plane>"),
        "t.scn"));
    ASSERT_EQ(s.geometry->primitives<DiskShape>().size(), 1u);
    ASSERT_EQ(s.geometry->planes().size(), 1u);
    EXPECT_NEAR(length(s.geometry->primitives<DiskShape>()[0].normal), 1.0, 1e-15);
    EXPECT_NEAR(length(s.geometry->planes()[0].normal), 1.0, 1e-15);
  }
  EXPECT_NE(test::errorMessage([] {
              parseScene(withObject("<disk><center>0,0,0</center><normal>0,0,0</normal><radius>1"
                                    "</radius><material>matte</material></disk>"),
                         "t.scn");
            }).find("a non-zero disk normal"),
            std::string::npos);
}

TEST(ShapeKinds, RequiredParametersAndOtherKindsParametersAreRefusedAtTheirLine) {
  for (const ShapeKindSpec& kind : shapeKinds()) {
    SCOPED_TRACE(kind.name);
    for (const ShapeParameter& p : kind.params()) {
      if (!p.required || p.attribute) continue;
      std::string object = exampleObject(kind);
      const std::string open = "<" + std::string(p.spec.name) + ">";
      const size_t a = object.find(open);
      const size_t b = object.find("</" + std::string(p.spec.name) + ">", a);
      object.erase(a, b + open.size() + 1 - a);
      EXPECT_EQ(errorMessage([&] { parseScene(withObject(object), "t.scn"); }),
                "t.scn:1: expected " + open + " inside <" + kind.name + ">, found none");
    }
    // A parameter only other kinds take.
    for (const ShapeKindSpec& other : shapeKinds())
      for (const ShapeParameter& p : other.params()) {
        if (p.attribute || shapeParameter(kind, p.spec.name)) continue;
        const std::string object = exampleObject(
            kind, "<" + std::string(p.spec.name) + ">" + p.spec.example + "</" + p.spec.name + ">");
        const std::string e = errorMessage([&] { parseScene(withObject(object), "t.scn"); });
        EXPECT_EQ(e.rfind("t.scn:1: expected one of <material>", 0), 0u) << e;
        EXPECT_NE(e.find("inside <" + std::string(kind.name) + ">, found <" + p.spec.name + ">"),
                  std::string::npos)
            << e;
      }
  }
}

TEST(ShapeKinds, ShapeMaterialAndObjectNamesDoNotCollide) {
  std::set<std::string> material;
  for (const ParamSpec& p : materialParameters()) material.insert(p.name);
  for (const ShapeKindSpec& kind : shapeKinds())
    for (const ShapeParameter& p : kind.params()) {
      EXPECT_FALSE(material.count(p.spec.name)) << kind.name << " " << p.spec.name;
      for (const char* appearance : {"material", "emission", "medium"})
        EXPECT_NE(std::string(p.spec.name), appearance) << kind.name;
    }
}

TEST(MediumKinds, EveryKindBuildsFromItsExamplesInEveryShapeThatHoldsOne) {
  for (const MediumKindSpec& kind : mediumKinds()) {
    SCOPED_TRACE(kind.name);
    EXPECT_EQ(findMediumKind(kind.name), &kind);
    std::string medium = std::string("<medium type=\"") + kind.name + "\">";
    for (const TakenParameter& p : kind.params()) {
      const std::string name = p.spec.name;
      if (name.ends_with("_scale")) continue;
      const TakenParameter* scale = mediumParameter(kind, name + "_scale");
      medium += "<" + name + (scale ? std::string(" scale=\"") + scale->spec.example + "\"" : "") +
                ">" + p.spec.example + "</" + name + ">";
    }
    medium += "</medium>";
    for (const ShapeKindSpec& shape : shapeKinds()) {
      const std::string object = exampleObject(shape, medium);
      if (!shape.holdsMedium) {
        EXPECT_NE(
            errorMessage([&] { parseScene(withObject(object), "t.scn"); }).find("found <medium>"),
            std::string::npos)
            << shape.name;
        continue;
      }
      const SceneDesc d = parseScene(withObject(object), "t.scn");
      ASSERT_TRUE(d.objects[0].medium.has_value()) << shape.name;
      for (const TakenParameter& p : kind.params())
        EXPECT_TRUE(d.objects[0].medium->params.has(p.spec.name))
            << shape.name << " " << p.spec.name;
      const RenderScene s = buildRenderScene(d);
      ASSERT_EQ(s.media.size(), 1u) << shape.name;
      EXPECT_TRUE(s.hasMedia);
      EXPECT_TRUE(s.media[0].dye && s.media[0].emission) << shape.name;
      EXPECT_NEAR(s.media[0].g, *d.objects[0].medium->params.number("g"), 1e-6);
    }
    // Unknown kinds are refused with the list of kinds.
    EXPECT_NE(errorMessage([&] {
                parseScene(withObject("<sphere><center>0,0,0</center><radius>1</radius>"
                                      "<material>interface</material><medium type=\"fog\">"
                                      "<sigma_a>1</sigma_a><sigma_s>1</sigma_s></medium></sphere>"),
                           "t.scn");
              }).find("expected a medium type " + mediumKindList() + ", found 'fog'"),
              std::string::npos);
  }
}

} // namespace
} // namespace nx

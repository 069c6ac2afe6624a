#include "integrators/lights/light_sampler.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "accel/closed_mesh.h"
#include "core/frame.h"
#include "core/math_util.h"
#include "core/ray_offset.h"
#include "integrators/integrator.h"
#include "integrators/lights/spherical_triangle.h"
#include "integrators/lights/triangle_sampling.h"
#include "integrators/sampling.h"

namespace nx {
namespace {

double triangleArea(const TriangleShape& t) {
  return 0.5 * length(cross(t.b - t.a, t.c - t.a));
}

// Bounds of triangles of a mesh (both faces emit: the cone of their normals, taken as two-sided
// when weighed), their area as power.
template <class Triangles>
LightBounds triangleBounds(const TriangleMesh& mesh, Triangles&& triangles) {
  LightBounds b;
  for (const size_t t : triangles) {
    const TriangleShape c = mesh.corners(t);
    const Vec3d nd = cross(c.b - c.a, c.c - c.a);
    const double len = length(nd);
    if (!(len > 0)) continue;
    LightBounds one;
    one.add(Vec3(c.a));
    one.add(Vec3(c.b));
    one.add(Vec3(c.c));
    one.normals = {Vec3(nd * (1 / len)), 1.0f};
    one.power = static_cast<float>(0.5 * len);
    b = unionOf(b, one);
  }
  return b;
}

// Completes a sample at point q of an emitter's surface (unit normal `normal` there, of its
// triangle or part `prim` of shape `shape` of kind `kind`) seen from pd: direction, distance,
// point and normal; `pdf` in solid angle, or negative for a point drawn with density
// `areaDensity` per unit area (d^2 / |cos| times it in solid angle). False where the
// configuration is degenerate.
bool finishFlatSample(const Vec3d& pd, const Vec3d& q, const Vec3d& normal, double pdf,
                      double areaDensity, uint32_t shape, uint32_t prim, LightSample& out,
                      ShapeKind kind = ShapeKind::Triangle) {
  const Vec3d toLight = q - pd;
  const double d2 = dot(toLight, toLight);
  if (!(d2 > 0)) return false;
  const double d = std::sqrt(d2);
  const Vec3d wi = toLight * (1.0 / d);
  const double cosLight = std::abs(dot(normal, wi));
  if (!(cosLight > 0)) return false;
  if (pdf < 0) pdf = areaDensity * d2 / cosLight;
  if (!std::isfinite(pdf) || !(pdf > 0)) return false;
  out.wi = Vec3(wi);
  out.distance = static_cast<float>(d);
  out.p = Vec3(q);
  // Error of the point's combination in double, then rounding to float.
  out.pError = roundingError(out.p);
  out.n = Vec3(normal);
  out.pdf = static_cast<float>(pdf);
  out.kind = kind;
  out.shape = shape;
  out.prim = prim;
  return true;
}

// The sign that turns mesh m's (b - a) x (c - a) outward when it is closed, else 0.
int outwardSign(const TriangleMesh& m) {
  const MeshClosure c = meshClosure(m);
  return !c.closed ? 0 : (c.volume > 0 ? 1 : (c.volume < 0 ? -1 : 0));
}

// Radius of a sphere around the scene's bounded shapes and the camera: the uniform background's
// power is that of the radiance falling on it (4 pi^2 R^2 L).
double sceneRadius(const RenderScene& scene) {
  BoundingBox b = scene.geometry->bounds();
  b.add(scene.camera.position());
  return std::max(1e-3, 0.5 * length(b.hi - b.lo));
}

// A light's spectrum met by a column so unevenly (E[g^2] / E[g]^2 over the column's choice)
// is worth the guided draw's cost: about a quarter of a sample's time
// (docs/performance.md, "Fluorescence under a narrow lamp").
constexpr double kGuidedMismatch = 1.25;

} // namespace

LightSampler::LightSampler(const RenderScene& scene, LightSelection selection,
                           TriangleLightSampling triangles)
    : scene_(&scene), selection_(selection), triangleSampling_(triangles) {
  addPrimitiveLights(LightKind::Cone);
  addMeshLights();
  addPrimitiveLights(LightKind::Area);
  addListedLights();
  addBackground();
  if (selection_ == LightSelection::Local && count() > kMaxLocalLights)
    selection_ = LightSelection::Tree;
  assignGroupsAndSources();
  weighBySamplingSpectra();
  if (selection_ == LightSelection::Tree) buildTree();
  buildExcitationGuides();
  buildChoiceTables();
}

void LightSampler::addPrimitiveLights(LightKind which) {
  const RenderScene& scene = *scene_;
  const GeometryScene& geometry = *scene.geometry;
  forEachAnalyticKind([&]<class P>() {
    constexpr bool cone = SamplesSolidAngle<P>;
    if ((which == LightKind::Cone) != cone) return;
    constexpr ShapeKind kind = kShapeKindOf<P>;
    const std::vector<ShapeAppearance>& apps = scene.shapes(kind);
    std::vector<int32_t>& lightOf = primitiveLight_[static_cast<size_t>(kind)];
    lightOf.assign(apps.size(), -1);
    for (size_t i = 0; i < apps.size(); ++i) {
      if (apps[i].emission < 0) continue;
      const P& shape = geometry.primitives<P>()[i];
      const Spectrum* e = &scene.emission[static_cast<size_t>(apps[i].emission)];
      const double le = tracedIntegral(*e);
      lightOf[i] = static_cast<int32_t>(lights_.size());
      if constexpr (cone) { // weighed by its bounding sphere's cone
        const auto [center, radius] = shape.boundingSphere();
        lights_.push_back({LightKind::Cone,
                           kind,
                           static_cast<uint32_t>(i),
                           -1,
                           e,
                           0,
                           0,
                           shape.fluxPerRadiance() * le,
                           le,
                           Vec3(center),
                           static_cast<float>(radius),
                           -1,
                           -1,
                           {}});
      } else { // bounds: box, normals, power the area (localWeight multiplies by the radiance)
        const double area = shape.area();
        const BoundingBox box = shape.bounds();
        LightBounds b;
        b.add(Vec3(box.lo)), b.add(Vec3(box.hi));
        const std::optional<Vec3d> facing = shape.facing();
        b.normals = facing ? DirectionCone{Vec3(*facing), 1.0f} : DirectionCone::all();
        b.power = static_cast<float>(area);
        b.twoSided = true;
        lights_.push_back({LightKind::Area, kind, static_cast<uint32_t>(i), -1, e, area, 0,
                           kPi * area * le * 2, le, b.center(), length(b.hi - b.lo) * 0.5f, -1, -1,
                           LightCluster(b)});
      }
    }
  });
}

void LightSampler::addMeshLights() {
  const RenderScene& scene = *scene_;
  const GeometryScene& geometry = *scene.geometry;
  auto emissionOf = [&](const ShapeAppearance& a) {
    return &scene.emission[static_cast<size_t>(a.emission)];
  };
  meshLight_.assign(scene.meshes.size(), -1);
  triangleLight_.resize(scene.meshes.size());
  for (size_t m = 0; m < scene.meshes.size(); ++m) {
    const MeshAppearance& app = scene.meshes[m];
    const TriangleMesh& mesh = geometry.meshes()[m];
    if (app.perTriangle.empty()) {
      if (app.whole.emission < 0) continue;
      Light l{LightKind::Mesh,
              ShapeKind::Triangle,
              static_cast<uint32_t>(m),
              -1,
              emissionOf(app.whole),
              0,
              areaCdf_.size(),
              0,
              0,
              Vec3(),
              0,
              -1,
              -1,
              {}};
      for (size_t t = 0; t < mesh.triangleCount(); ++t) {
        l.area += triangleArea(mesh.corners(t));
        areaCdf_.push_back(l.area);
      }
      if (!(l.area > 0)) continue;
      // Rectangles sampled whole, large meshes through a light tree (solid-angle sampling).
      std::optional<Rectangle> rectangle;
      if (triangleSampling_ == TriangleLightSampling::SolidAngle) rectangle = rectangleOf(mesh);
      if (rectangle) {
        l.rectangle = static_cast<int32_t>(rectangles_.size());
        RectangleLight r{*rectangle, frameOf(*rectangle), {}};
        for (size_t t = 0; t < 2; ++t) { // the frame's normal, turned as the triangle winds
          const TriangleShape c = mesh.corners(t);
          r.normal[t] = dot(cross(c.b - c.a, c.c - c.a), r.frame.z) < 0 ? -r.frame.z : r.frame.z;
        }
        rectangles_.push_back(r);
      } else if (triangleSampling_ == TriangleLightSampling::SolidAngle &&
                 mesh.triangleCount() > kSolidAngleChoice) {
        l.tree = static_cast<int32_t>(trees_.size());
        trees_.emplace_back(mesh, outwardSign(mesh));
      }
      if (l.tree >= 0) {
        l.bounds = trees_[static_cast<size_t>(l.tree)].bounds();
      } else {
        std::vector<size_t> all(mesh.triangleCount());
        for (size_t t = 0; t < all.size(); ++t) all[t] = t;
        l.bounds = LightCluster(triangleBounds(mesh, all));
      }
      // Both faces emit: power 2 pi A integral(L).
      l.radiance = tracedIntegral(*l.emission);
      l.power = 2 * kPi * l.area * l.radiance;
      BoundingBox box;
      for (uint32_t v = 0; v < mesh.vertexCount(); ++v) box.add(Vec3d(mesh.position(v)));
      l.center = Vec3((box.lo + box.hi) * 0.5);
      l.radius = static_cast<float>(0.5 * length(box.hi - box.lo));
      meshLight_[m] = static_cast<int32_t>(lights_.size());
      lights_.push_back(l);
      continue;
    }
    triangleLight_[m].assign(mesh.triangleCount(), -1);
    for (size_t t = 0; t < mesh.triangleCount(); ++t) {
      if (app.perTriangle[t].emission < 0) continue;
      Light l{LightKind::Mesh,
              ShapeKind::Triangle,
              static_cast<uint32_t>(m),
              static_cast<int32_t>(t),
              emissionOf(app.perTriangle[t]),
              triangleArea(mesh.corners(t)),
              0,
              0,
              0,
              Vec3(),
              0,
              -1,
              -1,
              {}};
      if (!(l.area > 0)) continue;
      l.radiance = tracedIntegral(*l.emission);
      l.power = 2 * kPi * l.area * l.radiance;
      const TriangleShape c = mesh.corners(t);
      l.bounds = LightCluster(triangleBounds(mesh, std::array<size_t, 1>{t}));
      l.center = Vec3((c.a + c.b + c.c) * (1.0 / 3));
      l.radius =
          static_cast<float>(std::max({length(c.a - Vec3d(l.center)), length(c.b - Vec3d(l.center)),
                                       length(c.c - Vec3d(l.center))}));
      triangleLight_[m][t] = static_cast<int32_t>(lights_.size());
      lights_.push_back(l);
    }
  }
}

void LightSampler::addListedLights() {
  const RenderScene& scene = *scene_;
  for (size_t i = 0; i < scene.lights.size(); ++i)
    std::visit(
        [&](const auto& light) {
          using Kind = std::decay_t<decltype(light)>;
          if constexpr (Kind::kInfinite)
            environments_.push_back(static_cast<int32_t>(lights_.size()));
          lights_.push_back({Kind::kInfinite ? LightKind::Environment : LightKind::Point,
                             ShapeKind::Plane, // (unused: not a shape)
                             static_cast<uint32_t>(i),
                             -1,
                             nullptr,
                             0,
                             0,
                             light.power(Kind::kInfinite ? sceneRadius(scene) : 0.0),
                             light.tracedPeak(),
                             light.center(),
                             0,
                             -1,
                             -1,
                             {}});
        },
        scene.lights[i]);
}

void LightSampler::addBackground() {
  const RenderScene& scene = *scene_;
  if (scene.background) {
    const double r = sceneRadius(scene);
    background_ = static_cast<int32_t>(lights_.size());
    const double le = tracedIntegral(*scene.background);
    lights_.push_back({LightKind::Background,
                       ShapeKind::Plane, // (unused: not a shape)
                       0,
                       -1,
                       &*scene.background,
                       0,
                       0,
                       4 * kPi * kPi * r * r * le,
                       le,
                       Vec3(0, 0, 0),
                       0,
                       -1,
                       -1,
                       {}});
  }
}

void LightSampler::assignGroupsAndSources() {
  const RenderScene& scene = *scene_;
  // Each light's group (light groups) and relight source: an emitting shape's by its emission,
  // a <light>'s by its place in the list, the background's its own.
  const LightGroups& groups = scene.lightGroups;
  for (const Light& l : lights_) {
    // Which of the tables and which entry: emission index, light index, or the background.
    int32_t emission = -1, light = -1;
    switch (l.kind) {
    case LightKind::Cone:
    case LightKind::Area:
      emission = scene.shapes(l.surface)[l.shape].emission;
      break;
    case LightKind::Mesh:
      emission = scene.meshes[l.shape]
                     .of(l.triangle < 0 ? 0u : static_cast<uint32_t>(l.triangle))
                     .emission;
      break;
    case LightKind::Point:
    case LightKind::Environment:
      light = static_cast<int32_t>(l.shape);
      break;
    case LightKind::Background:
      break;
    }
    auto of = [&](const std::vector<uint16_t>& ofEmission, const std::vector<uint16_t>& ofLight,
                  uint16_t ofBackground) -> uint16_t {
      if (emission >= 0)
        return static_cast<size_t>(emission) < ofEmission.size()
                   ? ofEmission[static_cast<size_t>(emission)]
                   : uint16_t{0};
      if (light >= 0)
        return static_cast<size_t>(light) < ofLight.size() ? ofLight[static_cast<size_t>(light)]
                                                           : uint16_t{0};
      return ofBackground;
    };
    group_.push_back(of(groups.ofEmission, groups.ofLight, groups.ofBackground));
    source_.push_back(of(groups.sourceOfEmission, groups.sourceOfLight, groups.sourceOfBackground));
  }
}

void LightSampler::weighBySamplingSpectra() {
  // A relightable build's emitters are flat unit spectra times their factors; a render told its
  // relighting targets weighs each by its source's sampling spectrum instead (the mean of its
  // targets): its radiance and power scaled by the spectrum's mean over the traced range.
  const std::vector<Spectrum>& sampling = scene_->relight.samplingOfSource;
  if (sampling.empty()) return;
  std::vector<double> mean;
  for (const Spectrum& s : sampling)
    mean.push_back(tracedIntegral(s) / (kTraceMaxNm - kTraceMinNm));
  for (size_t k = 0; k < lights_.size(); ++k) {
    lights_[k].radiance *= mean[source_[k]];
    lights_[k].power *= mean[source_[k]];
  }
}

void LightSampler::buildExcitationGuides() {
  const RenderScene& scene = *scene_;
  // Excitation guides, for scenes with a fluorescent surface only: the emission of shapes and
  // the background, a point or spot light's intensity, a flat guide for environment maps.
  if (std::any_of(scene.materials.begin(), scene.materials.end(),
                  [](const Material& m) { return m.reradiation != nullptr; })) {
    std::vector<const Spectrum*> spectra; // of guides_, to share one per spectrum
    const auto guideOf = [&](const Spectrum* s) {
      const auto known = std::find(spectra.begin(), spectra.end(), s);
      if (known == spectra.end()) {
        spectra.push_back(s);
        guides_.push_back(excitationGuideOf(s));
      }
      guideIndex_.push_back(
          static_cast<int32_t>(std::find(spectra.begin(), spectra.end(), s) - spectra.begin()));
    };
    const RelightSpectra& relight = scene.relight;
    for (size_t k = 0; k < lights_.size(); ++k) {
      const Light& l = lights_[k];
      guideFirst_.push_back(static_cast<uint32_t>(guideIndex_.size()));
      // A targeted relightable render: one guide per target of the light's group (its own
      // spectrum, as built, is the flat unit).
      if (!relight.targetsOfSource.empty()) {
        for (const Spectrum& t : relight.targetsOfSource[source_[k]]) guideOf(&t);
        continue;
      }
      const Spectrum* s = l.emission;
      if (l.kind == LightKind::Point)
        std::visit(
            [&](const auto& light) {
              if constexpr (requires { light.intensity; }) s = &light.intensity;
            },
            scene.lights[l.shape]);
      guideOf(s);
    }
    guideFirst_.push_back(static_cast<uint32_t>(guideIndex_.size()));
    // Where guiding pays, per fluorescent material and guide: emission bins whose column meets
    // the light unevenly (ReradiationMatrix::guideMismatch above kGuidedMismatch).
    for (const Material& m : scene.materials) {
      if (!m.reradiation || guides_.empty()) {
        fluorescentSlot_.push_back(-1);
        continue;
      }
      fluorescentSlot_.push_back(static_cast<int32_t>(guideWorth_.size() / guides_.size()));
      for (const ExcitationGuide& g : guides_) {
        std::bitset<ReradiationMatrix::kBins> worth;
        for (int o = 0; o < ReradiationMatrix::kBins; ++o)
          worth[static_cast<size_t>(o)] = m.reradiation->guideMismatch(g, o) > kGuidedMismatch;
        guideWorth_.push_back(worth);
      }
    }
  }
}

void LightSampler::buildChoiceTables() {
  // Choice probabilities: by power (uniform when every power is zero or not finite).
  double total = 0;
  for (const Light& l : lights_) total += l.power;
  const bool byPower = selection_ != LightSelection::Uniform && total > 0 && std::isfinite(total);
  double running = 0;
  for (const Light& l : lights_) {
    const double p = byPower ? l.power / total : 1.0 / static_cast<double>(lights_.size());
    pmf_.push_back(static_cast<float>(p));
    running += p;
    cdf_.push_back(running);
  }
  if (!cdf_.empty()) cdf_.back() = 1.0;
}

void LightSampler::buildTree() {
  // Each bounded light's bounds in the units of its Local weight (radiance times solid angle
  // far away): power cos / d^2 with power the radiance times the area (a sphere's projected
  // area, a closed mesh's a quarter of its area seen from outside, MeshLightTree::importance)
  // or a point light's peak intensity.
  const GeometryScene& geometry = *scene_->geometry;
  std::vector<SceneLightTree::Item> items;
  for (size_t k = 0; k < lights_.size(); ++k) {
    const Light& l = lights_[k];
    LightBounds b;
    switch (l.kind) {
    case LightKind::Point:
      b.add(l.center);
      std::visit(
          [&](const auto& light) {
            if constexpr (!std::decay_t<decltype(light)>::kInfinite)
              b.normals = light.emissionCone();
          },
          scene_->lights[l.shape]);
      b.cosEmission = 1; // a cone holds all its light
      b.power = static_cast<float>(l.radiance);
      break;
    case LightKind::Cone: // its bounding sphere
      b.add(l.center - Vec3(l.radius, l.radius, l.radius));
      b.add(l.center + Vec3(l.radius, l.radius, l.radius));
      b.normals = DirectionCone::all();
      b.power = static_cast<float>(l.radiance * kPi * l.radius * l.radius);
      break;
    case LightKind::Mesh: {
      const TriangleMesh& mesh = geometry.meshes()[l.shape];
      if (l.triangle >= 0) {
        const TriangleShape c = mesh.corners(static_cast<size_t>(l.triangle));
        b.add(Vec3(c.a)), b.add(Vec3(c.b)), b.add(Vec3(c.c));
      } else {
        for (uint32_t v = 0; v < mesh.vertexCount(); ++v) b.add(mesh.position(v));
      }
      b.normals = {l.bounds.axis, l.bounds.cosSpread};
      b.twoSided = true;
      const bool closed = l.tree >= 0 && trees_[static_cast<size_t>(l.tree)].closed();
      b.power = static_cast<float>(l.radiance * l.area * (closed ? 0.25 : 1.0));
      break;
    }
    case LightKind::Area: // the bounds it weighs itself with, its power the radiance's
      b.add(l.bounds.center - Vec3(l.bounds.radius, l.bounds.radius, l.bounds.radius));
      b.add(l.bounds.center + Vec3(l.bounds.radius, l.bounds.radius, l.bounds.radius));
      b.normals = {l.bounds.axis, l.bounds.cosSpread};
      b.twoSided = true;
      b.power = static_cast<float>(l.radiance * l.area);
      break;
    case LightKind::Background:
    case LightKind::Environment:
      unbounded_.push_back(static_cast<int32_t>(k));
      continue;
    }
    items.push_back({static_cast<int32_t>(k), b});
  }
  tree_ = SceneLightTree(items, lights_.size(), kLightTreeBucket);
}

float LightSampler::localWeight(const Light& l, const Vec3& p, const Vec3& n) const {
  const Vec3 toCenter = l.center - p;
  const float d2 = dot(toCenter, toCenter);
  const float r2 = l.radius * l.radius;
  const bool receiver = !(n == Vec3());
  // The receiver's |cos| towards a light seen within a cone of sin^2 = sin2 around the
  // direction to its centre, at its largest over the cone (1 without a receiver).
  const auto receiverCos = [&](float sin2) {
    if (!receiver || !(d2 > 0)) return 1.0f;
    const float cosI = std::min(1.0f, std::abs(dot(n, toCenter)) / std::sqrt(d2));
    const float sinI = std::sqrt(std::max(0.0f, 1 - cosI * cosI));
    const float sinU = std::sqrt(std::clamp(sin2, 0.0f, 1.0f)), cosU = std::sqrt(1 - sinU * sinU);
    return cosOfClampedDifference(cosI, sinI, cosU, sinU);
  };
  float solidAngle = 0;
  switch (l.kind) {
  case LightKind::Point: // intensity (the fraction sent towards p: a spot's cone) |cos| / d^2
    solidAngle = std::visit(
                     [&](const auto& light) {
                       if constexpr (!std::decay_t<decltype(light)>::kInfinite)
                         return light.fractionToward(p);
                       else
                         return 1.0f; // unreachable: infinite lights are Environment
                     },
                     scene_->lights[l.shape]) *
                 receiverCos(0) / std::max(d2, 1e-30f);
    break;
  case LightKind::Cone: // the cone of its bounding sphere (all of it, for a sphere)
    solidAngle = d2 <= r2 ? static_cast<float>(4 * kPi)
                          : static_cast<float>(2 * kPi * oneMinusCosFromSin2(r2 / d2)) *
                                receiverCos(r2 / d2);
    break;
  case LightKind::Mesh:   // at most a hemisphere of one face; the bound of its emitters when far
  case LightKind::Area: { // a curved surface (a cylinder) seen from inside: the whole sphere
    const float most = static_cast<float>((l.kind == LightKind::Area ? 4 : 2) * kPi);
    solidAngle =
        d2 <= r2 ? most
                 : std::min(most, l.tree >= 0 ? trees_[static_cast<size_t>(l.tree)].importance(p, n)
                                              : l.bounds.importance(p, n, true));
    break;
  }
  case LightKind::Background: // |cos| over the sphere integrates to 2 pi
  case LightKind::Environment:
    solidAngle = static_cast<float>((receiver ? 2 : 4) * kPi);
    break;
  }
  // Never zero for a light that emits: every light that can shine keeps a chance.
  return std::max(static_cast<float>(l.radiance) * solidAngle, 1e-30f) *
         (l.radiance > 0 ? 1.0f : 0.0f);
}

float LightSampler::treeProbability(int k, const Vec3& p, const Vec3& n) const {
  const auto leafWeight = [&](int j) { return localWeight(lights_[static_cast<size_t>(j)], p, n); };
  float total = tree_.weight(p, n, leafWeight);
  const float ofTree = total;
  for (const int32_t j : unbounded_) total += leafWeight(j);
  if (!(total > 0)) return 0;
  if (!tree_.holds(k)) return leafWeight(k) / total;
  return static_cast<float>(ofTree / total * tree_.probability(k, p, n, leafWeight));
}

int LightSampler::chooseInTree(const Vec3& p, const Vec3& n, double uc, double& share,
                               double& uRest) const {
  // The tree as one entry beside each unbounded light, by weight; then down the tree.
  const auto leafWeight = [&](int j) { return localWeight(lights_[static_cast<size_t>(j)], p, n); };
  const float ofTree = tree_.weight(p, n, leafWeight);
  std::array<float, 8> others{};
  float total = ofTree;
  for (size_t i = 0; i < unbounded_.size(); ++i) {
    const float w = leafWeight(unbounded_[i]);
    if (i < others.size()) others[i] = w;
    total += w;
  }
  if (!(total > 0)) return -1;
  double target = uc * total;
  if (target < ofTree || unbounded_.empty()) {
    double u = std::min(target / ofTree, 1.0 - 0x1p-53), inTree = 0;
    const int k = tree_.choose(p, n, u, inTree, leafWeight);
    share = ofTree / total * inTree;
    uRest = u;
    return k;
  }
  target -= ofTree;
  for (size_t i = 0; i < unbounded_.size(); ++i) {
    const float w = i < others.size() ? others[i] : leafWeight(unbounded_[i]);
    if (w > 0 && (target < w || i + 1 == unbounded_.size())) {
      share = w / total;
      uRest = std::clamp(target / w, 0.0, 1.0 - 0x1p-53);
      return unbounded_[i];
    }
    target -= w;
  }
  return -1;
}

float LightSampler::probability(int k, const Vec3& p, const Vec3& n, float weightTotal) const {
  if (selection_ == LightSelection::Tree && lights_.size() > 1) return treeProbability(k, p, n);
  if (selection_ != LightSelection::Local || lights_.size() == 1)
    return pmf_[static_cast<size_t>(k)];
  // The same sum, in the same order, as choose() (bit for bit the same total).
  float total = weightTotal;
  if (!(total > 0))
    for (const Light& l : lights_) total += localWeight(l, p, n);
  return total > 0 ? localWeight(lights_[static_cast<size_t>(k)], p, n) / total : 0.0f;
}

SampledSpectrum LightSampler::environmentRadiance(int i, const Vec3& d,
                                                  const SampledWavelengths& lambda) const {
  const Light& l = lights_[static_cast<size_t>(environments_[static_cast<size_t>(i)])];
  return std::visit(
      [&](const auto& light) {
        if constexpr (std::decay_t<decltype(light)>::kInfinite)
          return light.radiance(d, lambda);
        else
          return SampledSpectrum(); // unreachable: environments_ holds infinite lights only
      },
      scene_->lights[l.shape]);
}

float LightSampler::pdfEnvironment(int i, const Vec3& p, const Vec3& d, const Vec3& n,
                                   float weightTotal) const {
  const int k = environments_[static_cast<size_t>(i)];
  const Light& l = lights_[static_cast<size_t>(k)];
  const float pdf = std::visit(
      [&](const auto& light) {
        if constexpr (std::decay_t<decltype(light)>::kInfinite)
          return light.pdf(d);
        else
          return 0.0f; // unreachable: environments_ holds infinite lights only
      },
      scene_->lights[l.shape]);
  return pdf * probability(k, p, n, weightTotal);
}

float LightSampler::pdfBackground(const Vec3& p, const Vec3& n, float weightTotal) const {
  return background_ < 0
             ? 0.0f
             : static_cast<float>(1.0 / (4 * kPi)) * probability(background_, p, n, weightTotal);
}

int LightSampler::choose(const Vec3& p, const Vec3& n, float uChoice, float& shareOut, float& uRest,
                         float* weightTotal) const {
  if (lights_.empty()) return -1;
  // The first light whose running probability exceeds uChoice; uChoice is then rescaled to
  // [0, 1) within that light's share, for the light's own choice of triangle.
  const double uc = uChoice;
  size_t k;
  double lo, share;
  if (lights_.size() == 1) {
    k = 0, lo = 0, share = 1;
  } else if (selection_ == LightSelection::Tree) {
    k = 0, lo = 0, share = 0;
    double rest = 0;
    const int chosen = chooseInTree(p, n, uc, share, rest);
    if (chosen < 0 || !(share > 0)) return -1;
    uRest = static_cast<float>(std::min(rest, 0.99999994));
    shareOut = static_cast<float>(share);
    return chosen;
  } else if (selection_ == LightSelection::Local) {
    // Each weight computed once, kept on the stack (at most kMaxLocalLights: no allocation).
    std::array<float, kMaxLocalLights> weights;
    float total = 0;
    for (size_t i = 0; i < lights_.size(); ++i) total += weights[i] = localWeight(lights_[i], p, n);
    if (weightTotal) *weightTotal = total;
    if (!(total > 0)) return -1;
    const double target = uc * total;
    double running = 0;
    k = lights_.size() - 1;
    lo = 0, share = 0;
    for (size_t i = 0; i < lights_.size(); ++i) {
      const double w = weights[i];
      if (target < running + w || i + 1 == lights_.size()) {
        k = i, lo = running / total, share = w / total;
        break;
      }
      running += w;
    }
  } else {
    k = std::min(static_cast<size_t>(std::upper_bound(cdf_.begin(), cdf_.end(), uc) - cdf_.begin()),
                 lights_.size() - 1);
    lo = k == 0 ? 0.0 : cdf_[k - 1];
    share = pmf_[k];
  }
  if (!(share > 0)) return -1;
  uRest = static_cast<float>(std::clamp((uc - lo) / std::max(share, 1e-300), 0.0, 0.99999994));
  shareOut = static_cast<float>(share);
  return static_cast<int>(k);
}

bool LightSampler::sampleChosen(int k, float share, const Vec3& p, float uRest, Sample2 u,
                                const SampledWavelengths& lambda, LightSample& out,
                                const Vec3& n) const {
  if (!sampleLight(k, p, uRest, u, lambda, out, n)) return false;
  if (!out.delta)
    out.pdf *= share;
  else
    out.pdf = share;
  return true;
}

bool LightSampler::sample(const Vec3& p, float uChoice, Sample2 u, const SampledWavelengths& lambda,
                          LightSample& out, const Vec3& n, float* weightTotal) const {
  float share = 0, uRest = 0;
  const int k = choose(p, n, uChoice, share, uRest, weightTotal);
  return k >= 0 && sampleChosen(k, share, p, uRest, u, lambda, out, n);
}

size_t LightSampler::triangleCount(int k) const {
  const Light& l = lights_[static_cast<size_t>(k)];
  if (l.kind != LightKind::Mesh || l.triangle >= 0) return 1;
  return scene_->geometry->meshes()[l.shape].triangleCount();
}

bool LightSampler::sampleLight(int k, const Vec3& p, float uChoice, Sample2 u,
                               const SampledWavelengths& lambda, LightSample& out,
                               const Vec3& n) const {
  const Light& l = lights_[static_cast<size_t>(k)];
  out.delta = false;
  out.infinite = false;
  out.light = k;
  switch (l.kind) {
  case LightKind::Point: // a light of the scene's list: its kind samples it (static dispatch)
  case LightKind::Environment:
    return std::visit([&](const auto& light) { return light.sample(p, u, lambda, out); },
                      scene_->lights[l.shape]);
  case LightKind::Cone:
    if (!sampleCone(l, p, u, out)) return false;
    break;
  case LightKind::Mesh:
    if (!sampleMesh(l, p, n, uChoice, u, out)) return false;
    break;
  case LightKind::Area:
    if (!sampleArea(l, p, u, out)) return false;
    break;
  case LightKind::Background:
    out.wi = sampleUniformSphere(u);
    out.distance = INFINITY;
    out.pdf = static_cast<float>(1.0 / (4 * kPi));
    out.infinite = true;
    break;
  }
  out.radiance = evaluate(*l.emission, lambda);
  return true;
}

// A direction by the solid angle the primitive subtends (its sampleSolidAngle).
bool LightSampler::sampleCone(const Light& l, const Vec3& p, Sample2 u, LightSample& out) const {
  const std::optional<SolidAngleSample> s =
      scene_->geometry->visitPrimitive(l.surface, l.shape, [&](const auto& shape) {
        if constexpr (SamplesSolidAngle<std::decay_t<decltype(shape)>>)
          return shape.sampleSolidAngle(p, u);
        else
          return std::optional<SolidAngleSample>(); // not a Cone light's primitive
      });
  if (!s) return false;
  out.wi = s->wi;
  out.distance = static_cast<float>(s->distance);
  out.p = Vec3(s->p);
  out.pError = roundingError(out.p);
  out.n = Vec3(s->n);
  out.pdf = static_cast<float>(s->pdf);
  out.kind = l.surface;
  out.shape = l.shape;
  out.prim = s->part;
  return true;
}

// A point uniformly by area, drawn by the primitive (its sampleArea): density 1 / area,
// d^2 / (|cos| area) in solid angle.
bool LightSampler::sampleArea(const Light& l, const Vec3& p, Sample2 u, LightSample& out) const {
  const AreaSample s = scene_->geometry->visitPrimitive(
      l.surface, l.shape, [&](const auto& shape) { return shape.sampleArea(u); });
  return finishFlatSample(Vec3d(p), s.p, s.n, -1, 1 / l.area, l.shape, s.part, out, l.surface);
}

int LightSampler::chooseTriangle(const Light& l, const Vec3d& p, const Vec3& normal,
                                 float uTriangle, double& probability,
                                 std::array<SphericalTriangle, kSolidAngleChoice>& seen) const {
  const TriangleMesh& mesh = scene_->geometry->meshes()[l.shape];
  probability = 1;
  if (l.triangle >= 0) return l.triangle;
  if (l.tree >= 0)
    return trees_[static_cast<size_t>(l.tree)].choose(Vec3(p), normal, uTriangle, probability);
  const size_t n = mesh.triangleCount();
  if (triangleSampling_ == TriangleLightSampling::SolidAngle && n <= kSolidAngleChoice) {
    // A small mesh (a quad, a few triangles): each triangle in proportion to its solid angle,
    // so the whole mesh is sampled uniformly in solid angle where every triangle is.
    double total = 0;
    for (size_t t = 0; t < n; ++t)
      total += (seen[t] = sphericalTriangle(mesh.corners(t), p)).solidAngle;
    if (!(total > 0)) return -1;
    const double target = static_cast<double>(uTriangle) * total;
    double running = 0;
    for (size_t t = 0; t < n; ++t) {
      running += seen[t].solidAngle;
      if (seen[t].solidAngle > 0 && (target < running || t + 1 == n)) {
        probability = seen[t].solidAngle / total;
        return static_cast<int>(t);
      }
    }
    for (size_t t = n; t-- > 0;) // rounding left target past the last positive triangle
      if (seen[t].solidAngle > 0) {
        probability = seen[t].solidAngle / total;
        return static_cast<int>(t);
      }
    return -1;
  }
  // A triangle of the whole mesh in proportion to its area.
  const auto first = areaCdf_.begin() + static_cast<std::ptrdiff_t>(l.firstCdf);
  const auto last = first + static_cast<std::ptrdiff_t>(n);
  const double target = static_cast<double>(uTriangle) * l.area;
  const size_t t =
      std::min(static_cast<size_t>(std::upper_bound(first, last, target) - first), n - 1);
  probability = triangleArea(mesh.corners(t)) / l.area;
  return static_cast<int>(t);
}

double LightSampler::trianglePdf(const Light& l, const Vec3d& p, const Vec3& n, uint32_t t,
                                 const Vec3d& q, const Vec3d& wi) const {
  const TriangleMesh& mesh = scene_->geometry->meshes()[l.shape];
  const TriangleShape tri = mesh.corners(t);
  double choice = 1;
  SphericalTriangle seen; // triangle t from p, when a small mesh's choice saw it
  const SphericalTriangle* known = nullptr;
  if (l.tree >= 0) {
    choice = trees_[static_cast<size_t>(l.tree)].probability(t, Vec3(p), n);
    if (!(choice > 0)) return 0;
  } else if (l.triangle < 0) {
    const size_t count = mesh.triangleCount();
    if (triangleSampling_ == TriangleLightSampling::SolidAngle && count <= kSolidAngleChoice) {
      double total = 0;
      for (size_t j = 0; j < count; ++j) {
        const SphericalTriangle o = sphericalTriangle(mesh.corners(j), p);
        total += o.solidAngle;
        if (j == t) seen = o, known = &seen;
      }
      if (!(total > 0) || !(seen.solidAngle > 0)) return 0;
      choice = seen.solidAngle / total;
    } else {
      choice = triangleArea(tri) / l.area;
    }
  }
  SphericalTriangle st;
  if (triangleSampling_ == TriangleLightSampling::SolidAngle &&
      worthSphericalSampling(tri, p, st, known)) {
    if (n == Vec3()) return choice / st.solidAngle;
    // The warp's density at the square's point that maps to wi.
    const Sample2 u = invertSphericalTriangleSample(st, wi);
    return choice * cosineWarp(st, Vec3d(n)).pdf(u) / st.solidAngle;
  }
  // By area within the triangle: d^2 / (|cos| A_t) in solid angle.
  const Vec3d nd = cross(tri.b - tri.a, tri.c - tri.a);
  const double nLen = length(nd);
  const Vec3d toLight = q - p;
  const double cosLight = std::abs(dot(nd, wi)) / nLen;
  const double pdf = choice * dot(toLight, toLight) / (cosLight * 0.5 * nLen);
  return std::isfinite(pdf) ? pdf : 0.0;
}

bool LightSampler::sampleMesh(const Light& l, const Vec3& p, const Vec3& n, float uTriangle,
                              Sample2 u, LightSample& out) const {
  if (l.rectangle >= 0) return sampleRectangle(l, p, n, u, out);
  const TriangleMesh& mesh = scene_->geometry->meshes()[l.shape];
  const Vec3d pd(p);
  std::array<SphericalTriangle, kSolidAngleChoice> seen;
  double choice = 1;
  const int chosen = chooseTriangle(l, pd, n, uTriangle, choice, seen);
  if (chosen < 0) return false;
  const size_t t = static_cast<size_t>(chosen);
  const TriangleShape tri = mesh.corners(t);
  const Vec3d nd = cross(tri.b - tri.a, tri.c - tri.a);
  const double nLen = length(nd);
  if (!(nLen > 0)) return false;
  // A small mesh's choice has seen its triangles already.
  const bool smallMesh = l.triangle < 0 && l.tree < 0 && mesh.triangleCount() <= kSolidAngleChoice;
  SphericalTriangle st;
  double b1, b2, pdf;
  Vec3d wi;
  if (triangleSampling_ == TriangleLightSampling::SolidAngle &&
      worthSphericalSampling(tri, pd, st, smallMesh ? &seen[t] : nullptr)) {
    // Uniform in the solid angle it subtends (Arvo 1995); the point is where that direction
    // meets the triangle (barycentrics by Moeller-Trumbore, clamped into it).
    // With a receiver normal, the square's point first drawn in proportion to the cosines
    // towards the corners (cosineWarp), so the direction roughly follows the projected solid
    // angle.
    const double warp = applyCosineWarp(st, n, u);
    if (!sampleSphericalTriangle(st, u, wi)) return false;
    const Vec3d e1 = tri.b - tri.a, e2 = tri.c - tri.a, s = pd - tri.a;
    const Vec3d pv = cross(wi, e2), qv = cross(s, e1);
    const double det = dot(e1, pv);
    if (!(std::abs(det) > 0)) return false;
    b1 = std::clamp(dot(s, pv) / det, 0.0, 1.0);
    b2 = std::clamp(dot(wi, qv) / det, 0.0, 1.0 - b1);
    pdf = choice * warp / st.solidAngle;
  } else {
    sampleUniformTriangle(u, b1, b2);
    pdf = -1; // from the point, below
  }
  // By area: the triangle's area density 1 / A_t times its choice (a large mesh chose by
  // area: choice / A_t = 1 / A).
  return finishFlatSample(pd, trianglePoint(tri, b1, b2), nd * (1.0 / nLen), pdf,
                          choice / (0.5 * nLen), l.shape, static_cast<uint32_t>(t), out);
}

bool LightSampler::sampleRectangle(const Light& l, const Vec3& p, const Vec3& n, Sample2 u,
                                   LightSample& out) const {
  const RectangleLight& r = rectangles_[static_cast<size_t>(l.rectangle)];
  const Vec3d pd(p);
  SphericalRectangle sr;
  Vec3d q;
  double pdf = -1;
  if (worthSphericalSampling(r.frame, pd, sr)) {
    // Uniform in solid angle (Urena et al. 2013), after the receiver's cosine warp.
    const double warp = applyCosineWarp(sr, n, u);
    if (!sampleSphericalRectangle(sr, u, q)) return false;
    pdf = warp / sr.solidAngle;
  } else {
    q = r.shape.corner + r.shape.edgeX * static_cast<double>(u.u) +
        r.shape.edgeY * static_cast<double>(u.v);
  }
  // The triangle the point lies on: the first holds the corner, the diagonal is s + t = 1.
  const Vec3d fromCorner = q - r.frame.corner;
  const uint32_t prim =
      dot(fromCorner, r.frame.x) / r.frame.lengthX + dot(fromCorner, r.frame.y) / r.frame.lengthY <=
              1.0
          ? 0u
          : 1u;
  return finishFlatSample(pd, q, r.normal[prim], pdf, 1 / (r.frame.lengthX * r.frame.lengthY),
                          l.shape, prim, out);
}

double LightSampler::rectanglePdf(const Light& l, const Vec3d& p, const Vec3& n, const Vec3d& q,
                                  const Vec3d& wi) const {
  const RectangleLight& r = rectangles_[static_cast<size_t>(l.rectangle)];
  SphericalRectangle sr;
  if (worthSphericalSampling(r.frame, p, sr)) {
    if (n == Vec3()) return 1 / sr.solidAngle;
    return cosineWarp(sr, Vec3d(n)).pdf(invertSphericalRectangleSample(sr, q)) / sr.solidAngle;
  }
  const Vec3d toLight = q - p;
  const double pdf =
      dot(toLight, toLight) / (std::abs(dot(r.frame.z, wi)) * r.frame.lengthX * r.frame.lengthY);
  return std::isfinite(pdf) ? pdf : 0.0; // d^2 / (|cos| A)
}

int LightSampler::lightOf(const SurfaceHit& hit) const {
  if (hit.kind == ShapeKind::Triangle) {
    if (hit.index >= meshLight_.size()) return -1;
    if (!triangleLight_[hit.index].empty()) return triangleLight_[hit.index][hit.prim];
    return meshLight_[hit.index];
  }
  // A plane (infinite: never an emitter; its table stays empty) or an analytic primitive.
  const std::vector<int32_t>& of = primitiveLight_[static_cast<size_t>(hit.kind)];
  return hit.index < of.size() ? of[hit.index] : -1;
}

float LightSampler::pdf(const Vec3& p, const SurfaceHit& lightHit, const Vec3& wi, const Vec3& n,
                        float weightTotal) const {
  const int k = lightOf(lightHit);
  if (k < 0) return 0;
  const Light& l = lights_[static_cast<size_t>(k)];
  float pdf = 0;
  if (l.kind == LightKind::Cone) {
    pdf = static_cast<float>(
        scene_->geometry->visitPrimitive(l.surface, l.shape, [&](const auto& shape) {
          if constexpr (SamplesSolidAngle<std::decay_t<decltype(shape)>>)
            return shape.solidAnglePdf(p, wi);
          else
            return 0.0; // not a Cone light's primitive
        }));
  } else if (l.kind == LightKind::Area) { // d^2 / (|cos| area)
    const Vec3d toLight = Vec3d(lightHit.p) - Vec3d(p);
    const double cosLight = std::abs(dot(Vec3d(lightHit.ng), Vec3d(wi)));
    pdf = static_cast<float>(dot(toLight, toLight) / (cosLight * l.area));
    if (!std::isfinite(pdf)) return 0;
  } else {
    pdf = static_cast<float>(
        l.rectangle >= 0
            ? rectanglePdf(l, Vec3d(p), n, Vec3d(lightHit.p), Vec3d(wi))
            : trianglePdf(l, Vec3d(p), n, lightHit.prim, Vec3d(lightHit.p), Vec3d(wi)));
    if (!std::isfinite(pdf)) return 0;
  }
  return pdf * probability(k, p, n, weightTotal);
}

} // namespace nx

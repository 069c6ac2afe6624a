#pragma once
// Next-event estimation: choosing a light by its power and a direction towards it.

#include <array>
#include <bitset>
#include <vector>

#include "core/sampler.h"
#include "integrators/lights/light_bounds.h"
#include "integrators/lights/light_sample.h"
#include "integrators/lights/mesh_light_tree.h"
#include "integrators/lights/scene_light_tree.h"
#include "integrators/lights/spherical_rectangle.h"
#include "integrators/lights/spherical_triangle.h"
#include "integrators/render_scene.h"
#include "spectra/reradiation_matrix.h"

namespace nx {

/// How the light sampler chooses among the scene's lights.
enum class LightSelection : uint8_t {
  /// In proportion to the power each light can send to the shading point: its radiance
  /// integrated over the traced range times the solid angle it subtends there (intensity / d^2
  /// for point lights, times a spot's falloff towards the point; for triangles and meshes the
  /// bound of their LightBounds, which is zero where every emitter faces away), times the
  /// receiver's |cos| bounded over the light - the default. Scenes with more than
  /// kMaxLocalLights lights use Tree.
  Local,
  Power,   ///< in proportion to emitted power over the traced range, the same everywhere
  Uniform, ///< each light equally often
  /// Down a light tree over the bounded lights (SceneLightTree), each cluster weighed by the
  /// light it can send to the shading point (its box, its emitters' normals or cones) and each
  /// light at the leaves by Local's weight; the infinite lights (environment, background)
  /// weighed beside the tree's root by their Local weight.
  Tree,
};

/// Most lights for which LightSelection::Local weighs every light at every shading point; with
/// more it walks the light tree. Measured (docs/performance.md, "Choosing among many lights"):
/// weighing every light beats the tree up to 256 lights per band and up to about 512 in
/// luminance, the tree wins from 1024.
inline constexpr int kMaxLocalLights = 256;

/// Lights per bucket of the light tree (LightSelection::Tree), weighed exactly: buckets of 8
/// measured best at 1024 and 4096 lights (of 1, 4, 8, 16, 64; docs/performance.md).
inline constexpr int kLightTreeBucket = 8;

/// How emitting triangles (triangles, quads, meshes) are sampled from a shading point.
enum class TriangleLightSampling : uint8_t {
  /// Uniformly in the solid angle a triangle subtends (Arvo 1995) or a rectangle subtends
  /// (Urena et al. 2013), by area where that is tiny or nearly a hemisphere; a rectangle of
  /// two triangles is sampled whole, another mesh of at most kSolidAngleChoice triangles
  /// chooses its triangle by solid angle, a larger one through its MeshLightTree - the
  /// default.
  SolidAngle,
  Area, ///< a triangle by area, a uniform point on it (the strategy before; benchmarks)
};

/// Meshes of at most this many triangles choose theirs by solid angle (a quad is two; each
/// light sample keeps this many seen triangles on the stack); larger ones have a light tree.
inline constexpr size_t kSolidAngleChoice = kMeshLightTreeFrom;

/// The lights next-event estimation can aim at: point lights, emitting spheres (sampled through
/// the cone they subtend, or uniformly over directions from inside), emitting meshes and inline
/// triangles (TriangleLightSampling) and the uniform background (uniform directions). Emitting
/// planes are infinite: BSDF sampling alone finds them. Nothing is allocated after
/// construction.
class LightSampler {
public:
  /// The scene's lights, chosen by `selection`, their triangles sampled as `triangles` says.
  explicit LightSampler(const RenderScene& scene, LightSelection selection = LightSelection::Local,
                        TriangleLightSampling triangles = TriangleLightSampling::SolidAngle);

  /// Number of lights it can choose from.
  int count() const { return static_cast<int>(lights_.size()); }
  /// The selection in use (Local falls back to Tree beyond kMaxLocalLights lights).
  LightSelection selection() const { return selection_; }
  /// Probability that sample() chooses light k for shading point p of shading normal n (zero:
  /// none, in a medium). weightTotal: the sum of the Local weights at (p, n) as choose() found
  /// it there (0: unknown, summed again).
  float probability(int k, const Vec3& p, const Vec3& n, float weightTotal = 0) const;
  /// The kind of light k.
  LightKind kind(int k) const { return lights_[static_cast<size_t>(k)].kind; }
  /// Triangles light k samples among (1 for points, spheres and the background).
  size_t triangleCount(int k) const;
  /// The light group (RenderScene::lightGroups) light k belongs to.
  uint16_t group(int k) const { return group_[static_cast<size_t>(k)]; }
  /// The relight source (RelightSpectra) light k belongs to (0 unless relightable).
  uint16_t source(int k) const { return source_[static_cast<size_t>(k)]; }
  /// The light group of environment light i.
  uint16_t environmentGroup(int i) const {
    return group_[static_cast<size_t>(environments_[static_cast<size_t>(i)])];
  }
  /// The radiance spectrum light k emits (emitting shapes, the background), or null for a
  /// light of the scene's list (sceneLightOf).
  const Spectrum* emissionOf(int k) const { return lights_[static_cast<size_t>(k)].emission; }
  /// The index in RenderScene::lights of light k, or -1 when it is not one of them.
  int sceneLightOf(int k) const {
    const Light& l = lights_[static_cast<size_t>(k)];
    return l.kind == LightKind::Point || l.kind == LightKind::Environment
               ? static_cast<int>(l.shape)
               : -1;
  }
  /// Emitted power of light k over the traced range (W; the selection's weights).
  double power(int k) const { return lights_[static_cast<size_t>(k)].power; }
  /// The light tree (LightSelection::Tree; empty otherwise).
  const SceneLightTree& tree() const { return tree_; }

  /// A light chosen with uChoice, then a sample of it for shading point p (pdf includes the
  /// choice); false if there is no light or the configuration is degenerate. n: the shading
  /// normal at p, for the cosine warp of triangle lights (zero: none, e.g. in a medium).
  /// weightTotal, if given, receives choose()'s sum of weights (for pdf() at the same point).
  bool sample(const Vec3& p, float uChoice, Sample2 u, const SampledWavelengths& lambda,
              LightSample& out, const Vec3& n = Vec3(), float* weightTotal = nullptr) const;
  /// The light sample() chooses with uChoice for shading point p of shading normal n (zero:
  /// none), its probability `share` and uChoice rescaled to [0, 1) within its share (`uRest`,
  /// for the light's triangle); -1 if none can be chosen. weightTotal, if given, receives the
  /// sum of the Local weights at (p, n) (left as it is for other selections): passed back to
  /// pdf() at the same point, it spares weighing every light again for the MIS weight.
  int choose(const Vec3& p, const Vec3& n, float uChoice, float& share, float& uRest,
             float* weightTotal = nullptr) const;
  /// sample() for the light choose() gave: sampleLight with the choice's probability in pdf.
  bool sampleChosen(int k, float share, const Vec3& p, float uRest, Sample2 u,
                    const SampledWavelengths& lambda, LightSample& out,
                    const Vec3& n = Vec3()) const;
  /// Light k's excitation guides (for excitation sampling at fluorescent vertices): its
  /// spectrum on the re-radiation matrix's grid, or in a relightable render told its targets one
  /// per target of its group; none for scenes without a fluorescent surface. A light whose
  /// spectrum varies over it (an environment map) has a flat guide.
  ExcitationGuides excitationGuides(int k) const {
    ExcitationGuides out;
    if (guides_.empty()) return out;
    const size_t first = guideFirst_[static_cast<size_t>(k)],
                 end = guideFirst_[static_cast<size_t>(k) + 1];
    for (size_t i = first; i < end; ++i)
      out.guide[out.count++] = &guides_[static_cast<size_t>(guideIndex_[i])];
    return out;
  }
  /// Whether drawing the excitation guided by light k's guides pays at a vertex of
  /// `material` for some lane of lambda: its column meets one of them unevenly there
  /// (ReradiationMatrix::guideMismatch); false for a material that does not fluoresce.
  bool guidanceHelps(int k, uint32_t material, const SampledWavelengths& lambda) const {
    if (guides_.empty()) return false;
    const int32_t slot = fluorescentSlot_[material];
    if (slot < 0) return false;
    for (size_t g = guideFirst_[static_cast<size_t>(k)];
         g < guideFirst_[static_cast<size_t>(k) + 1]; ++g) {
      const auto& worth = guideWorth_[static_cast<size_t>(slot) * guides_.size() +
                                      static_cast<size_t>(guideIndex_[g])];
      for (int i = 0; i < kLanes; ++i) {
        const int o = ReradiationMatrix::binOf(lambda.lambda[i]);
        if (o >= 0 && worth[static_cast<size_t>(o)]) return true;
      }
    }
    return false;
  }
  /// A sample of light k itself (pdf without any choice probability); uChoice, in [0, 1),
  /// picks the triangle of a mesh light; n as for sample().
  bool sampleLight(int k, const Vec3& p, float uChoice, Sample2 u, const SampledWavelengths& lambda,
                   LightSample& out, const Vec3& n = Vec3()) const;

  /// Light number of the emitter a hit is on, or -1 if next-event estimation cannot sample it.
  int lightOf(const SurfaceHit& hit) const;
  /// Density (solid angle, with the choice probability) with which sample() returns direction
  /// wi from p towards the point `lightHit` (found by a ray from p along wi); 0 if that surface
  /// is not a light it samples. n: the shading normal sample() was given at p; weightTotal:
  /// what choose() gave there (0: unknown).
  float pdf(const Vec3& p, const SurfaceHit& lightHit, const Vec3& wi, const Vec3& n = Vec3(),
            float weightTotal = 0) const;
  /// Density with which sample() returns direction wi from p (shading normal n) towards the
  /// background; 0 without one. weightTotal as for pdf().
  float pdfBackground(const Vec3& p, const Vec3& n, float weightTotal = 0) const;

  /// Number of environment lights (infinite lights of the scene's list) a ray that leaves
  /// the scene sees.
  int environmentCount() const { return static_cast<int>(environments_.size()); }
  /// Radiance environment light i sends from direction d (d points away from the scene).
  SampledSpectrum environmentRadiance(int i, const Vec3& d, const SampledWavelengths& lambda) const;
  /// Density (solid angle, with the choice probability) with which sample() returns
  /// direction d from p (shading normal n) through environment light i; weightTotal as for
  /// pdf().
  float pdfEnvironment(int i, const Vec3& p, const Vec3& d, const Vec3& n,
                       float weightTotal = 0) const;

private:
  struct Light {
    LightKind kind;
    ShapeKind surface;        ///< Cone and Area lights: the primitive's kind (else unused)
    uint32_t shape;           ///< primitive (within its kind), mesh or point-light index
    int32_t triangle = -1;    ///< an inline triangle of the mesh, or -1 for the whole mesh
    const Spectrum* emission; ///< radiance, or a point light's intensity
    double area = 0;          ///< mesh lights: total area
    size_t firstCdf = 0;      ///< whole meshes: start of the triangles' area CDF in areaCdf_
    double power = 0;
    double radiance = 0; ///< integral of the emission over the traced range
    Vec3 center;         ///< bounding sphere (primitives, meshes) or position (points)
    float radius = 0;
    int32_t tree = -1;      ///< whole meshes of more than kSolidAngleChoice triangles: trees_
    int32_t rectangle = -1; ///< whole meshes forming a rectangle: rectangles_
    LightCluster bounds;    ///< meshes, triangles, Area lights: box, normals, area
  };
  /// Weight of light l at p (shading normal n) for LightSelection::Local (positive wherever
  /// it can shine).
  float localWeight(const Light& l, const Vec3& p, const Vec3& n) const;
  // The constructor's steps, in order: the lights of each source, then what is derived.
  /// Emitting analytic primitives: through the solid angle they subtend where they sample it
  /// (Cone: spheres), else uniformly by area (Area: disks, cylinders, ...).
  void addPrimitiveLights(LightKind which);
  /// Emitting meshes: whole (rectangles, meshes with a light tree, small meshes) or, where the
  /// triangles' emission differs, triangle by triangle.
  void addMeshLights();
  /// A point of an Area light uniformly by area, seen from p.
  bool sampleArea(const Light& l, const Vec3& p, Sample2 u, LightSample& out) const;
  /// The scene's <light> list (points, spots, environments).
  void addListedLights();
  /// The uniform background.
  void addBackground();
  /// Each light's light group and relight source.
  void assignGroupsAndSources();
  /// Excitation guides and where they pay (scenes with a fluorescent surface only).
  void buildExcitationGuides();
  /// Scales the lights' radiance and power by their sources' sampling spectra (a relightable
  /// render told its targets: RelightSpectra::samplingOfSource).
  void weighBySamplingSpectra();
  /// Power and Uniform's choice probabilities and their running sums.
  void buildChoiceTables();
  /// Builds tree_ and unbounded_ (LightSelection::Tree).
  void buildTree();
  /// Probability that LightSelection::Tree chooses light k at (p, n).
  float treeProbability(int k, const Vec3& p, const Vec3& n) const;
  /// LightSelection::Tree's choice: the light, its probability `share`, uc rescaled into it.
  int chooseInTree(const Vec3& p, const Vec3& n, double uc, double& share, double& uRest) const;
  /// A direction of a Cone light, by the solid angle its primitive subtends from p.
  bool sampleCone(const Light& l, const Vec3& p, Sample2 u, LightSample& out) const;
  bool sampleMesh(const Light& l, const Vec3& p, const Vec3& n, float uTriangle, Sample2 u,
                  LightSample& out) const;
  /// The triangle of mesh light l sampleMesh uses for uTriangle at p and its probability;
  /// `seen` holds a small mesh's triangles seen from p. -1 if none can be chosen.
  int chooseTriangle(const Light& l, const Vec3d& p, const Vec3& n, float uTriangle,
                     double& probability,
                     std::array<SphericalTriangle, kSolidAngleChoice>& seen) const;
  /// sampleMesh for a rectangle light.
  bool sampleRectangle(const Light& l, const Vec3& p, const Vec3& n, Sample2 u,
                       LightSample& out) const;
  /// Density (solid angle) of sampleRectangle returning wi from p towards point q.
  double rectanglePdf(const Light& l, const Vec3d& p, const Vec3& n, const Vec3d& q,
                      const Vec3d& wi) const;
  /// Density (solid angle, without the light's choice) of sampleMesh returning wi from p
  /// towards point q of triangle t of mesh light l, for receiver normal n (zero: none).
  double trianglePdf(const Light& l, const Vec3d& p, const Vec3& n, uint32_t t, const Vec3d& q,
                     const Vec3d& wi) const;

  const RenderScene* scene_;
  std::vector<Light> lights_;
  LightSelection selection_;
  TriangleLightSampling triangleSampling_;
  std::vector<float> pmf_;           ///< Power and Uniform: choice probabilities
  std::vector<double> cdf_;          ///< their running sum (cdf_[k] = P(light <= k))
  std::vector<double> areaCdf_;      ///< per whole-mesh light: running area of its triangles
  std::vector<MeshLightTree> trees_; ///< light trees of large mesh lights
  SceneLightTree tree_;              ///< LightSelection::Tree: over the bounded lights
  std::vector<int32_t> unbounded_;   ///< LightSelection::Tree: the lights beside the tree
  /// A rectangle light: its frame, and its two triangles' unit normals (the mesh's winding).
  struct RectangleLight {
    Rectangle shape;
    RectangleFrame frame;
    Vec3d normal[2];
  };
  std::vector<RectangleLight> rectangles_; ///< rectangle lights
  /// Light number per analytic primitive (index: ShapeKind, then the primitive), or -1.
  std::array<std::vector<int32_t>, kShapeKindCount> primitiveLight_;
  std::vector<int32_t> meshLight_;                  ///< light number per mesh (whole meshes), or -1
  std::vector<std::vector<int32_t>> triangleLight_; ///< per mesh with inline triangles
  int32_t background_ = -1;
  std::vector<int32_t> environments_;    ///< light numbers of the environment lights
  std::vector<uint16_t> group_;          ///< light group per light
  std::vector<uint16_t> source_;         ///< relight source per light
  std::vector<ExcitationGuide> guides_;  ///< one per light spectrum, for fluorescent scenes only
  std::vector<uint32_t> guideFirst_;     ///< per light (and one past): its first in guideIndex_
  std::vector<int32_t> guideIndex_;      ///< the lights' guides in guides_, light after light
  std::vector<int32_t> fluorescentSlot_; ///< per material: its row of guideWorth_, or -1
  /// Per (fluorescent material, guide): the emission bins where guiding pays.
  std::vector<std::bitset<ReradiationMatrix::kBins>> guideWorth_;
};

} // namespace nx

#pragma once
// The immutable scene the integrators render: geometry in Embree, spectra resolved,
// materials by index, no strings.

#include <array>
#include <memory>
#include <optional>
#include <vector>

#include "accel/geometry_scene.h"
#include "core/camera.h"
#include "integrators/lights/light_kinds.h"
#include "integrators/materials/material.h"
#include "integrators/media/homogeneous_medium.h"
#include "integrators/media/medium_stack.h"
#include "io/scene_desc.h"
#include "spectra/reradiation_matrix.h"
#include "spectra/sensor.h"
#include "spectra/spectrum.h"

namespace nx {

/// Largest spectral EXR a reflectance texture may be read from (bytes).
inline constexpr std::uintmax_t kMaxTextureFileBytes = 4ull << 30;

/// Per-shape appearance: material index and optional emitted radiance.
struct ShapeAppearance {
  uint32_t material = 0;
  int32_t emission = -1;   ///< index into RenderScene::emission, or -1
  uint32_t objectId = 0;   ///< 1 + the object's position among the scene file's objects
  uint32_t materialId = 0; ///< 1 + the index of the first object with the same material
  int32_t medium = -1;     ///< index into RenderScene::media of what fills the shape, or -1
  /// The shape bounds a volume (media scenes): +1 with its geometric normal pointing out (every
  /// sphere, closed meshes wound that way), -1 pointing in, 0 not closed.
  int8_t boundary = 0;
};

/// The appearance of a mesh: one for the whole mesh (a mesh file), or one per triangle (the
/// scene's inline triangles, gathered into one mesh).
struct MeshAppearance {
  ShapeAppearance whole;
  std::vector<ShapeAppearance> perTriangle; ///< empty: `whole` for every triangle
  /// The appearance of triangle t.
  const ShapeAppearance& of(uint32_t t) const {
    return perTriangle.empty() ? whole : perTriangle[t];
  }
};

/// Settings resolved from the scene file.
struct RenderSettings {
  int width = 0, height = 0;
  RenderMode mode = RenderMode::SpectralMcpt;
  int depth = 5;
  int samples = 16;
  uint32_t seed = 0;
  Sensor bands;
  std::string outputPath; ///< the scene's <path> (preview), possibly empty
};

/// A tabulated spectrum of the scene and the wavelengths its table covers.
struct TabulatedRange {
  std::string where; ///< "file:line" of the element
  std::string what;  ///< its name, file or "nm:value pairs"
  double loNm = 0, hiNm = 0;
  /// How the scene chooses what it does beyond ("": extrapolate="zero|hold" on the element).
  std::string choice{};
};

/// An imported EEM's emission window and the emission its ends still hold (shares of the
/// emission profile's peak): the matrix is 0 beyond the window, so a render tracing beyond an
/// end where emission remains misses the dye's light there (extrapolationWarnings says so).
struct EmissionWindow {
  std::string where; ///< "file:line" of the <eem> element
  std::string file;  ///< the EEM file
  double loNm = 0, hiNm = 0;
  double shareAtLo = 0, shareAtHi = 0; ///< the profile at each end over its peak
  /// Photons the imported matrix emits into each of its 5 nm bins, per unit excitation in
  /// every bin (ReradiationMatrix grid).
  std::vector<double> photonsPerBin;
};

/// Share of its peak an EEM's emission may keep at the end of its window before a render
/// tracing beyond warns (below it the dye's light beyond is negligible).
inline constexpr double kEmissionWindowEdgeShare = 0.01;

/// The scene's light groups: every emitter belongs to one, named by its group="NAME" (ungrouped
/// emitters form the group "default"); --aov lightgroups splits the image by group.
struct LightGroups {
  std::vector<std::string> names;   ///< group id -> name, in order of first appearance
  std::vector<uint16_t> ofEmission; ///< group of each RenderScene::emission
  std::vector<uint16_t> ofLight;    ///< group of each RenderScene::lights
  std::vector<uint16_t> ofMedium;   ///< group of each RenderScene::media (its emission)
  uint16_t ofBackground = 0;        ///< group of the background
  /// Relight source (RelightSpectra) of each emission, light and the background: filled by a
  /// relightable build (every emitter of one group with one spectrum shares a source), else 0.
  std::vector<uint16_t> sourceOfEmission, sourceOfLight;
  uint16_t sourceOfBackground = 0;
  /// The id of group `name`, added when new.
  uint16_t idOf(const std::string& name) {
    const std::string n = name.empty() ? "default" : name;
    for (size_t i = 0; i < names.size(); ++i)
      if (names[i] == n) return static_cast<uint16_t>(i);
    names.push_back(n);
    return static_cast<uint16_t>(names.size() - 1);
  }
};

/// The emitters' spectra of a relightable render (--relightable, docs/relighting.md): every
/// emitter is built as its factor kappa (its scale=, the measuring geometry of at= and flux=)
/// times a flat unit spectrum, and the spectrum written in the scene for it is applied to each
/// contribution at the wavelengths it left the emitter with. The transport per unit spectrum is
/// then what the film keeps, per source: the emitters of one light group with one spectrum.
struct RelightSpectra {
  bool enabled = false;
  std::vector<Spectrum> ofSource;      ///< per source: its emitters' spectrum
  std::vector<uint16_t> groupOfSource; ///< per source: its light group
  /// Per source, the spectrum its lights are chosen by and fluorescent excitation is guided
  /// by (relighting targets: the mixture of its group's targets, or its own spectrum for a group
  /// without one); empty without targets (lights chosen by their factors, excitation by the
  /// re-radiation matrices alone). It moves samples only: the transport stays per unit spectrum.
  std::vector<Spectrum> samplingOfSource;
  /// Per source, the targets its fluorescent excitation is guided by, one guide each (its own
  /// spectrum for a group without targets); empty without targets.
  std::vector<std::vector<Spectrum>> targetsOfSource;
  /// The name of source s: its group's, and ".2", ".3", ... for a group's further spectra (a
  /// group name holds no dot).
  std::string name(size_t s, const LightGroups& groups) const {
    int n = 1;
    for (size_t t = 0; t < s; ++t) n += groupOfSource[t] == groupOfSource[s];
    std::string out = groups.names[groupOfSource[s]];
    if (n > 1) out.append(".").append(std::to_string(n));
    return out;
  }
};

/// Everything an integrator needs, immutable after building.
struct RenderScene {
  RenderSettings settings;
  /// "file:line: warning: ..." notes of the build (what the scene asks for that renders, but
  /// not as asked: e.g. a medium too dense for float positions where it stands)
  std::vector<std::string> warnings;
  PinholeCamera camera{{0, 0, 0}, {0, 0, 1}, {0, 1, 0}, 60, 1, 1};
  /// The shapes and their BVH (with its Embree device), shared with other renders of the
  /// same shapes (accel/geometry_cache.h).
  std::shared_ptr<const GeometryScene> geometry;
  std::vector<Material> materials;
  /// What each object is called (index: object id - 1): its name="...", else the <material
  /// id> it uses, else "sphere at line 12 (matte)"; names a comparison's regions by object id
  std::vector<std::string> objectLabels;
  std::vector<Spectrum> emission; ///< emitted radiance spectra, W m^-2 sr^-1 nm^-1
  /// Each shape's appearance per kind (index: ShapeKind), parallel to the geometry's planes and
  /// analytic primitives; the triangles' are the meshes'
  std::array<std::vector<ShapeAppearance>, kShapeKindCount> shapeAppearances;
  std::vector<MeshAppearance> meshes; ///< parallel to the geometry's meshes
  std::vector<SceneLight> lights;     ///< the <light>s (points, spots, ...), in file order
  LightGroups lightGroups;            ///< which group each emitter belongs to
  RelightSpectra relight;             ///< the groups' spectra of a relightable build
  std::optional<Spectrum> background; ///< uniform environment radiance
  Spectrum previewWhite;              ///< illuminant the preview is white-balanced for
  size_t meshBytes = 0;               ///< bytes the meshes' buffers take
  bool hasFluorescence = false; ///< some material re-radiates (the fluorescent path tracer runs)
  std::vector<HomogeneousMedium> media; ///< the media filling spheres
  /// The path tracer with media runs: some shape holds a medium or is an interface.
  bool hasMedia = false;
  MediumStack cameraMedia; ///< the media the camera is inside (its spheres, outermost first)
  /// Digest of everything the scene was resolved from: its text and the bytes of every file
  /// it refers to (CSV spectra, matrices). Part of the render key of resume and merge.
  uint64_t contentDigest = 0;
  /// Tables the scene uses without an extrapolate="..." choice (zero beyond them), with their
  /// range: a render tracing beyond one warns (extrapolationWarnings).
  std::vector<TabulatedRange> tables;
  /// Imported EEMs' emission windows (a render tracing beyond one where emission remains warns).
  std::vector<EmissionWindow> emissionWindows;

  /// The reflectance of `material` at a hit for the lanes: its texture at the hit's uv (filled
  /// in for spheres here), else its spectrum.
  SampledSpectrum reflectanceAt(const Material& material, SurfaceHit& hit,
                                const SampledWavelengths& lambda) const {
    SampledSpectrum out;
    if (!material.texture) {
      material.reflectance.evaluate(lambda, out);
      return out;
    }
    surfaceUv(hit);
    return material.texture->evaluate(hit.u, hit.v, lambda);
  }

  /// The relative concentration of `material`'s dye at a hit: its concentration map at the
  /// hit's uv (filled in for spheres here), or 1 without a map.
  float concentrationAt(const Material& material, SurfaceHit& hit) const {
    if (!material.concentration) return 1;
    surfaceUv(hit);
    return material.concentration->at(hit.u, hit.v);
  }

  /// The appearances of the shapes of `kind` (a plane's or an analytic primitive's).
  const std::vector<ShapeAppearance>& shapes(ShapeKind kind) const {
    return shapeAppearances[static_cast<size_t>(kind)];
  }
  /// The appearances of the shapes of `kind`, to fill.
  std::vector<ShapeAppearance>& shapes(ShapeKind kind) {
    return shapeAppearances[static_cast<size_t>(kind)];
  }

  /// Appearance of the shape a hit is on.
  const ShapeAppearance& appearance(const SurfaceHit& hit) const {
    if (hit.kind == ShapeKind::Triangle) return meshes[hit.index].of(hit.prim);
    return shapes(hit.kind)[hit.index];
  }
};

/// Resolves a SceneDesc into a RenderScene: names to spectra (built-in or the scene's
/// <spectrum> definitions), CSV spectra and matrices read, RGB colours upsampled (rt and
/// mcpt), value ranges checked exactly over the traced range (reflectances within [0, 1],
/// emission >= 0, IOR within [1, 10] over 300-1100 nm), the Embree scene built. Errors carry the
/// file:line of the offending item.
RenderScene buildRenderScene(const SceneDesc& desc);

/// Warnings for the scene's tables that end inside [loNm, hiNm], the range a render traces:
/// "file:line: warning: spectrum '<what>' is tabulated over A-B nm ... (extrapolate=...)"; and
/// for imported EEMs whose emission window ends inside it with more than
/// kEmissionWindowEdgeShare of their peak emission at that end.
std::vector<std::string> extrapolationWarnings(const RenderScene& scene, double loNm, double hiNm);

/// The same checks and resolution without building the Embree scene (`geometry` stays null):
/// for tools that only validate scenes, such as the fuzzer.
RenderScene resolveRenderScene(const SceneDesc& desc);

} // namespace nx

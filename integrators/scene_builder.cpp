#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <tuple>

#include "accel/closed_mesh.h"
#include "accel/geometry_cache.h"
#include "accel/shape_kinds.h"
#include "core/error.h"
#include "core/math_util.h"
#include "core/text_table.h"
#include "integrators/lights/light_kinds.h"
#include "integrators/lights/measured_emitter.h"
#include "integrators/materials/bsdf.h"
#include "integrators/materials/material_kind.h"
#include "integrators/media/medium_kinds.h"
#include "integrators/relight_targets.h"
#include "integrators/render_scene.h"
#include "integrators/scene_references.h"
#include "io/camera_from_desc.h"
#include "io/mesh_reader.h"
#include "io/spectral_exr.h"
#include "io/texture_reader.h"
#include "spectra/colour.h"
#include "spectra/eem_import.h"
#include "spectra/illuminants.h"
#include "spectra/named_spectra.h"
#include "spectra/rgb_upsampling.h"
#include "spectra/spectrum_bounds.h"

namespace nx {
namespace {

// An emitter's spectrum as written in the scene and the factor on it (its scale=, the
// measuring geometry of at= or flux=).
struct EmitterSpectrum {
  Spectrum shape;
  double factor = 1;
};

class Builder {
public:
  explicit Builder(const SceneDesc& desc) : desc_(desc), refs_(desc), mediumInputs_(*this) {}

  // The settings, the camera, the preview's white, the relightable check and the background.
  void buildSettings(RenderScene& scene) const {
    const SettingsDesc& s = desc_.settings;
    scene.settings = {s.width, s.height, s.mode, s.depth, s.samples, s.seed, s.bands, s.outputPath};
    scene.camera = cameraFromDesc(desc_.camera, s.width, s.height);
    const bool spectral = s.mode == RenderMode::SpectralMcpt;

    scene.previewWhite =
        s.illuminant ? refs_.resolve(*s.illuminant, SpectrumRole::Emission) : *namedEmission("D65");
    // The preview is white-balanced from this white's chromaticity: it needs visible light.
    if (const Xyz w = spectrumToXyz(scene.previewWhite); s.illuminant && !(w.y > 0))
      throw Error(s.illuminant->loc.str() +
                  ": expected an <illum> with visible light (the preview's white balance "
                  "needs its colour), found luminance Y = " +
                  numberText(w.y));
    scene.relight.enabled = desc_.relightable;
    if (desc_.relightable && !spectral)
      throw Error(desc_.file +
                  ": --relightable: expected a spectral_mcpt scene (relighting "
                  "replaces emission spectra), found mode " +
                  std::string(renderModeName(s.mode)));
    if (s.background) {
      scene.lightGroups.ofBackground = scene.lightGroups.idOf(s.backgroundGroup);
      scene.background = traced(refs_.resolve(*s.background, SpectrumRole::Emission), 1.0,
                                scene.lightGroups.ofBackground, s.background->loc, scene,
                                scene.lightGroups.sourceOfBackground);
    }
  }

  // The closed meshes of a scene with media, (volume, mesh), each marked as a boundary of the
  // side its triangles face; a <medium> in a mesh that is not closed is an error.
  std::vector<std::pair<double, size_t>>
  closedMeshBoundaries(RenderScene& scene, const std::vector<TriangleMesh>& meshes,
                       const std::vector<std::pair<size_t, size_t>>& meshObjects) const {
    std::vector<std::pair<double, size_t>> closedMeshes; // (volume, mesh)
    for (const auto& [meshIndex, objectIndex] : meshObjects) {
      const ObjectDesc& o = desc_.objects[objectIndex];
      if (!scene.hasMedia) break;
      const MeshClosure c = meshClosure(meshes[meshIndex]);
      if (!c.closed && o.medium)
        throw Error(o.medium->loc.str() +
                    ": expected a closed mesh around a <medium> (every "
                    "edge shared by two triangles wound alike), found " +
                    c.problem + " in " +
                    (o.geometry.has("file") ? *o.geometry.get<std::string>("file") : o.shape));
      if (!c.closed) continue;
      scene.meshes[meshIndex].whole.boundary = c.volume > 0 ? 1 : -1;
      closedMeshes.emplace_back(std::abs(c.volume), meshIndex);
    }
    return closedMeshes;
  }

  // The material of object o (its id objectId): stored once per distinct description, the
  // kind and the canonical text of its parameters (a <material id>'s, or inline ones written
  // alike), so 16,000 triangles of one colour share one material and one upsampling fit; its
  // MaterialId is the first object using that description.
  uint32_t sharedMaterial(const ObjectDesc& o, uint32_t objectId, bool spectral,
                          RenderScene& scene) {
    const bool emitter = o.emission.has_value();
    const MaterialDesc& md =
        o.materialRef.empty() ? static_cast<const MaterialDesc&>(o) : namedMaterial(o.materialRef);
    const std::string text = identityText(md, emitter);
    if (auto it = materialByText_.find(text); it != materialByText_.end()) return it->second;
    Material m = material(md, o.materialRef.empty() ? o.loc : namedMaterialLoc(o.materialRef),
                          emitter, spectral);
    m.reflectance = forRendering(m.reflectance);
    if (m.reradiation) scene.hasFluorescence = true;
    materialIdOf_.push_back(objectId);
    const auto index = static_cast<uint32_t>(scene.materials.size());
    scene.materials.push_back(std::move(m));
    materialByText_.emplace(text, index);
    return index;
  }

  RenderScene build(bool withGeometry) {
    RenderScene scene;
    const SettingsDesc& s = desc_.settings;
    const bool spectral = s.mode == RenderMode::SpectralMcpt;
    buildSettings(scene);

    AnalyticShapes analytic; // spheres, disks, cylinders, ...
    std::vector<PlaneShape> planes;
    std::vector<TriangleShape> triangles; // the inline triangles, gathered into one mesh
    MeshAppearance inlineTriangles;
    std::vector<TriangleMesh> meshes;
    std::vector<std::pair<size_t, size_t>> meshObjects; // (mesh, object) of meshes
    const ShapeKindInputs shapeInputs(*this);
    for (size_t objectIndex = 0; objectIndex < desc_.objects.size(); ++objectIndex) {
      const ObjectDesc& o = desc_.objects[objectIndex];
      scene.objectLabels.push_back(!o.name.empty() ? o.name
                                   : !o.materialRef.empty()
                                       ? o.materialRef
                                       : o.shape + " at line " + std::to_string(o.loc.line) + " (" +
                                             o.material + ")");
      ShapeAppearance app;
      app.objectId = static_cast<uint32_t>(objectIndex + 1);
      app.material = sharedMaterial(o, app.objectId, spectral, scene);
      app.materialId = materialIdOf_[app.material];
      // Surfaces light passes straight through need the path tracer that sees through them.
      if (materialLobes(scene.materials[app.material]) & kStraightTransmission)
        scene.hasMedia = true;
      if (o.medium) {
        app.medium = static_cast<int32_t>(scene.media.size());
        scene.media.push_back(medium(*o.medium));
        if (desc_.relightable && scene.media.back().emission)
          throw Error(o.medium->loc.str() +
                      ": --relightable: expected media that do not emit, found an emitting "
                      "medium (its emission is not relit; render it without --relightable)");
        scene.lightGroups.ofMedium.push_back(
            scene.media.back().emission ? scene.lightGroups.idOf(o.group) : 0);
        scene.hasMedia = true;
        if (scene.media.back().dye) scene.hasFluorescence = true;
      }
      // The kind's primitive, placed by its type: spheres and planes in their lists, inline
      // triangles gathered into one mesh, meshes (quads, files) one Embree geometry each.
      const ShapeKindSpec& kind = *findShapeKind(o.shape); // the loader checked the name
      ShapeGeometry geometry = shapeInputs.build(kind, o);
      if (auto e = emission(o, spectral, geometry)) {
        app.emission = static_cast<int32_t>(scene.emission.size());
        const uint16_t group = scene.lightGroups.idOf(o.group);
        uint16_t source = 0;
        scene.emission.push_back(
            traced(e->shape, e->factor, group, o.emission->loc, scene, source));
        scene.lightGroups.ofEmission.push_back(group);
        scene.lightGroups.sourceOfEmission.push_back(source);
      }
      double extent = 0; // how far from the origin it reaches (a medium's float resolution)
      std::visit(
          [&](auto& shape) {
            using Shape = std::decay_t<decltype(shape)>;
            if constexpr (std::is_same_v<Shape, PlaneShape>) {
              planes.push_back(shape);
              scene.shapes(ShapeKind::Plane).push_back(app);
            } else if constexpr (std::is_same_v<Shape, TriangleShape>) {
              triangles.push_back(shape);
              inlineTriangles.perTriangle.push_back(app);
            } else if constexpr (!std::is_same_v<Shape, TriangleMesh>) { // analytic
              const BoundingBox box = shape.bounds();
              for (const Vec3d& c : {box.lo, box.hi})
                extent = std::max({extent, std::abs(c.x), std::abs(c.y), std::abs(c.z)});
              std::get<std::vector<Shape>>(analytic).push_back(shape);
              app.boundary = kind.holdsMedium ? 1 : 0; // closed, normals outward
              scene.shapes(kShapeKindOf<Shape>).push_back(app);
            } else {
              for (uint32_t v = 0; v < shape.vertexCount(); ++v) {
                const Vec3 p = shape.position(v);
                extent = std::max(
                    {extent, double(std::abs(p.x)), double(std::abs(p.y)), double(std::abs(p.z))});
              }
              meshes.push_back(std::move(shape));
              scene.meshes.push_back({app, {}});
              meshObjects.emplace_back(meshes.size() - 1, objectIndex);
            }
          },
          geometry);
      if (o.medium)
        warnIfBelowFloatPrecision(scene.media.back(), o.medium->loc, extent, scene.warnings);
    }
    for (const LightDesc& l : desc_.lights) {
      const uint16_t group = scene.lightGroups.idOf(l.group);
      std::optional<Spectrum> shape;
      scene.lights.push_back(light(l, spectral, &shape));
      if (desc_.relightable) {
        if (std::holds_alternative<EnvironmentLight>(scene.lights.back()))
          throw Error(l.loc.str() +
                      ": --relightable: expected lights of one spectrum each, found an "
                      "environment map (each texel has its own; use <background> for a uniform "
                      "sky, or render without --relightable)");
      }
      scene.lightGroups.ofLight.push_back(group);
      scene.lightGroups.sourceOfLight.push_back(
          desc_.relightable && shape ? relightSource(*shape, group, l.loc, scene) : uint16_t{0});
    }
    if (desc_.relightable)
      setRelightTargets(scene, desc_.relightTargets);
    else if (!desc_.relightTargets.empty())
      throw Error(desc_.file + ": " + desc_.relightTargets.front().option +
                  ": only with --relightable (the targets a relightable render draws for)");
    if (!triangles.empty()) {
      meshes.push_back(TriangleMesh::fromTriangles(triangles));
      scene.meshes.push_back(std::move(inlineTriangles));
    }
    // In scenes with media, closed meshes are boundaries the paths' medium stacks follow.
    const std::vector<std::pair<double, size_t>> closedMeshes =
        closedMeshBoundaries(scene, meshes, meshObjects);
    if (scene.hasMedia && s.mode == RenderMode::Rt)
      throw Error(s.modeLoc.str() +
                  ": expected <mode> spectral_mcpt or mcpt for a scene with media, interface or "
                  "thin_glass surfaces (rt traces neither), found rt");
    scene.cameraMedia =
        cameraMedia(scene.camera.position(), analytic, scene, closedMeshes, meshes, scene.meshes);
    scene.meshBytes = 0;
    for (const TriangleMesh& m : meshes) scene.meshBytes += m.bytes();
    scene.contentDigest = refs_.digest();
    scene.tables = refs_.tables();
    scene.emissionWindows = emissionWindows_;
    scene.warnings.insert(scene.warnings.end(), warnings_.begin(), warnings_.end());
    scene.warnings.insert(scene.warnings.end(), refs_.warnings().begin(), refs_.warnings().end());
    if (!withGeometry) return scene;
    scene.geometry = sharedGeometry(std::move(analytic), std::move(planes), std::move(meshes));
    return scene;
  }

private:
  // What makes two materials the same (shared, one MaterialId): the kind, whether the object
  // emits (an emitter without a reflectance is black), and the canonical text of the
  // parameters (one serialisation: core/params/parameter_set.h).
  static std::string identityText(const MaterialDesc& m, bool emitter) {
    return m.material + (emitter ? ";emitter;" : ";;") + m.params.canonicalText();
  }

  // The definition of a <material id> (the loader checked that it exists).
  const MaterialDesc& namedMaterial(const std::string& id) const {
    for (const NamedMaterialDesc& m : desc_.materials)
      if (m.id == id) return m.material;
    throw Error("no material '" + id + "'"); // unreachable after loading
  }
  const SourceLocation& namedMaterialLoc(const std::string& id) const {
    for (const NamedMaterialDesc& m : desc_.materials)
      if (m.id == id) return m.loc;
    throw Error("no material '" + id + "'"); // unreachable after loading
  }

  // A <medium>: its coefficients resolved and checked over the traced range.
  // Positions are floats: where a medium stands `extent` from the origin they are resolved to
  // about extent * 2^-23. A mean free path within 50 of those steps is walked with a relative
  // error above 2% per flight (measured: a white sphere of mean free path 0.1 at 1e5 from the
  // origin 1.5% dark, at 3e4 within noise; 1e-4 at 1e4, 33% dark), so the build says so.
  static void warnIfBelowFloatPrecision(const HomogeneousMedium& m, const SourceLocation& loc,
                                        double extent, std::vector<std::string>& warnings) {
    const double sigmaT = spectrumExtremes(m.sigmaA, kTraceMinNm, kTraceMaxNm).max +
                          spectrumExtremes(m.sigmaS, kTraceMinNm, kTraceMaxNm).max + m.dyePeak;
    const double spacing = extent * std::ldexp(1.0, -23), meanFreePath = 1 / sigmaT;
    if (sigmaT > 0 && spacing > 0.02 * meanFreePath)
      warnings.push_back(loc.str() + ": warning: the medium's shortest mean free path (" +
                         numberText(meanFreePath) + " units) is within 50 steps of the float " +
                         "resolution of positions where it stands (" + numberText(spacing) +
                         " units, " + numberText(extent) + " from the origin): its flights are " +
                         "walked imprecisely and it renders darker; move the scene nearer the " +
                         "origin or give it in larger units");
  }

  // A <medium>: its kind's build (the loader checked the kind's name).
  HomogeneousMedium medium(const MediumDesc& d) const {
    return findMediumKind(d.kind)->build(d.params, mediumInputs_);
  }

  // The media of the spheres and closed meshes containing the camera, outermost (largest)
  // first.
  // (Primitives that bound a volume say whether it holds a point: volume() and contains().)
  static MediumStack cameraMedia(const Vec3d& eye, const AnalyticShapes& analytic,
                                 const RenderScene& scene,
                                 const std::vector<std::pair<double, size_t>>& closedMeshes,
                                 const std::vector<TriangleMesh>& meshes,
                                 const std::vector<MeshAppearance>& meshApps) {
    std::vector<std::pair<double, int32_t>> around; // (volume, medium)
    forEachAnalyticKind([&]<class P>() {
      const std::vector<P>& shapes = std::get<std::vector<P>>(analytic);
      const std::vector<ShapeAppearance>& apps = scene.shapes(kShapeKindOf<P>);
      for (size_t i = 0; i < shapes.size(); ++i)
        if constexpr (requires { shapes[i].contains(eye); })
          if (apps[i].boundary != 0 && shapes[i].contains(eye))
            around.emplace_back(shapes[i].volume(), apps[i].medium);
    });
    for (const auto& [volume, mesh] : closedMeshes)
      if (insideClosedMesh(meshes[mesh], eye))
        around.emplace_back(volume, meshApps[mesh].whole.medium);
    std::sort(around.begin(), around.end(),
              [](const auto& a, const auto& b) { return a.first > b.first; });
    MediumStack stack;
    for (const auto& entry : around) stack.enter(entry.second);
    return stack;
  }

  // What the medium kinds' builds ask of the scene (integrators/media/homogeneous_medium.h).
  class MediumKindInputs : public MediumInputs {
  public:
    explicit MediumKindInputs(const Builder& b) : b_(b) {}
    Spectrum spectrum(const SpectrumDesc& d, SpectrumRole role) const override {
      return b_.refs_.resolve(d, role);
    }
    void checkEmission(const Spectrum& s, const SourceLocation& where) const override {
      SceneReferences::checkEmission(s, where);
    }
    FluorescenceModel fluorescenceModel(const FluorescenceDesc& f) const override {
      return b_.fluorescence(f);
    }
    void warn(const std::string& message) const override { b_.warnings_.push_back(message); }

  private:
    const Builder& b_;
  };

  // What the shape kinds' builds ask of the scene (accel/shape_schema.h): mesh files read,
  // their bytes folded into the content digest; errors name the object's line.
  class ShapeKindInputs : public ShapeInputs {
  public:
    explicit ShapeKindInputs(const Builder& b) : b_(b) {}
    TriangleMesh meshFile(const std::string& path, const AffineDesc& t) const override {
      MeshFile f = readMeshFile(path);
      b_.refs_.fold(f.bytes, path);
      f.mesh.transform(t.m, t.t);
      if (const std::string problem = f.mesh.validate(); !problem.empty())
        throw Error("mesh '" + path + "' after its <transform>: " + problem);
      return std::move(f.mesh);
    }
    void warn(const std::string& message) const override {
      b_.warnings_.push_back(building_->str() + ": warning: " + message);
    }
    // The object's primitive from its kind's build.
    ShapeGeometry build(const ShapeKindSpec& kind, const ObjectDesc& o) const {
      building_ = &o.loc;
      try {
        return kind.build(o.geometry, *this);
      } catch (const Error& e) {
        throw Error(o.loc.str() + ": " + e.what());
      }
    }

  private:
    const Builder& b_;
    mutable const SourceLocation* building_ = nullptr; ///< the object being built
  };

  // What the light kinds' builds ask of the scene (integrators/lights/light_kind.h).
  class LightKindInputs : public LightInputs {
  public:
    explicit LightKindInputs(const Builder& b) : b_(b) {}
    Spectrum spectrum(const SpectrumDesc& d, SpectrumRole role) const override {
      return b_.refs_.resolve(d, role);
    }
    Spectrum srgbIntensity(const std::array<double, 3>& rgb) const override {
      try {
        return upsampleSrgbIlluminant({rgb[0], rgb[1], rgb[2]});
      } catch (const Error& e) {
        throw Error(loc.str() + ": " + e.what());
      }
    }
    void checkEmission(const Spectrum& s, const SourceLocation& where) const override {
      SceneReferences::checkEmission(s, where);
    }
    Spectrum emitted(const Spectrum& shape, double factor) const override {
      if (!relightShape) return forRendering(shape.scaled(factor));
      *relightShape = forRendering(shape);
      return Spectrum(ConstantSpectrum{1.0}, factor);
    }
    /// Set in a relightable build: where emitted() leaves the light's spectrum.
    std::optional<Spectrum>* relightShape = nullptr;
    std::shared_ptr<const SpectralImage> spectralImage(const std::string& path,
                                                       const SourceLocation& where) const override {
      try {
        (void)b_.refs_.readFile(path, kMaxTextureFileBytes, "environment map");
        return std::make_shared<const SpectralImage>(readSpectralExr(path));
      } catch (const Error& e) {
        const std::string what = e.what();
        throw Error(where.str() + ": " + (what.rfind(path, 0) == 0 ? "" : path + ": ") + what);
      }
    }
    void tabulated(const SourceLocation& where, const std::string& what, double loNm, double hiNm,
                   const std::string& choice) const override {
      b_.refs_.noteTable({where.str(), what, loNm, hiNm, choice});
    }

  private:
    const Builder& b_;
  };

  // A light from its kind's build; its parameters are checked against the kind's declarations
  // (the loader read them so; Python edits are checked again here).
  SceneLight light(const LightDesc& l, bool spectral, std::optional<Spectrum>* shape) const {
    const LightKindSpec* kind = findLightKind(l.kind);
    if (!kind)
      throw Error(l.loc.str() + ": expected a light type " + lightKindList() + ", found '" +
                  l.kind + "'");
    for (const Parameter& p : l.params.items())
      if (!lightParameter(*kind, p.name))
        throw Error(p.loc.str() + ": expected no <" + p.name + "> on a " + kind->name +
                    " light, found one");
    for (const LightParameter& p : kind->params())
      if (p.required && !l.params.has(p.spec.name))
        throw Error(l.loc.str() + ": expected <" + p.spec.name + "> inside <light>, found none");
    LightKindInputs in(*this);
    in.spectral = spectral;
    in.loc = l.loc;
    if (desc_.relightable) in.relightShape = shape;
    return kind->build(l.params, in);
  }

  // What the kinds' builds ask of the scene (integrators/materials/material_kind.h).
  class KindInputs : public MaterialInputs {
  public:
    explicit KindInputs(const Builder& b) : b_(b) {}
    Spectrum spectrum(const SpectrumDesc& d, SpectrumRole role) const override {
      return b_.refs_.resolve(d, role);
    }
    void warn(const std::string& message) const override { b_.warnings_.push_back(message); }
    IorModel ior(const IorDesc& d) const override { return b_.iorModel(d); }
    FluorescenceModel fluorescenceModel(const FluorescenceDesc& d) const override {
      return b_.fluorescence(d);
    }
    std::shared_ptr<const ReradiationMatrix> measuredMatrix(const FluorescenceDesc& d,
                                                            const Spectrum* rho) const override {
      try {
        if (d.matrix) { // given as numbers (Python): checked, its content in the render key
          checkMeasuredMatrix(*d.matrix, "the measured matrix");
          b_.refs_.fold(canonicalText(ParamValue(d)), "the measured matrix");
          return std::make_shared<const ReradiationMatrix>(
              ReradiationMatrix::fromMeasured(*d.matrix, rho));
        }
        if (d.eem) return b_.importedEem(d, rho);
        return std::make_shared<const ReradiationMatrix>(ReradiationMatrix::fromMeasured(
            parseMeasuredMatrixCsv(b_.refs_.readFile(*d.matrixCsv, 64u << 20, "table file"),
                                   *d.matrixCsv),
            rho));
      } catch (const Error& e) {
        throw Error(d.loc.str() + ": " + e.what());
      }
    }
    std::shared_ptr<const ReflectanceTexture> texture(const SpectrumDesc& d) const override {
      return b_.texture(d);
    }
    std::shared_ptr<const ConcentrationMap>
    concentrationMap(const FluorescenceDesc& d) const override {
      if (d.concentration) { // given as numbers (Python): its content in the render key
        b_.refs_.fold(std::to_string(d.concentration->digest), "the concentration map");
        return d.concentration;
      }
      try {
        return std::make_shared<const ConcentrationMap>(parseConcentrationCsv(
            b_.refs_.readFile(*d.concentrationCsv, 64u << 20, "table file"), *d.concentrationCsv));
      } catch (const Error& e) {
        throw Error(d.loc.str() + ": " + e.what());
      }
    }
    Spectrum srgbReflectance(const std::array<double, 3>& rgb) const override {
      try {
        return upsampleSrgbReflectance({rgb[0], rgb[1], rgb[2]});
      } catch (const Error& e) {
        throw Error(objectLoc.str() + ": " + e.what());
      }
    }

  private:
    const Builder& b_;
  };

  // A material from its kind's build, its parameters checked against the kind's schema first
  // (the loader did so for the file; Python edits are checked again here).
  Material material(const MaterialDesc& o, const SourceLocation& objectLoc, bool emitter,
                    bool spectral) const {
    const MaterialKindSpec* kind = findMaterialKind(o.material);
    if (!kind)
      throw Error(o.materialLoc.str() + ": expected a material " + materialKindList() +
                  ", found '" + o.material + "'");
    checkMaterialParameters(*kind, o.params);
    KindInputs in(*this);
    in.emitter = emitter;
    in.spectral = spectral;
    in.objectLoc = objectLoc;
    in.kindName = o.material;
    return kind->build(*kind, o.params, in);
  }

  // A reflectance texture: the built-in chart, a spectral EXR checked to hold reflectances,
  // or a PNG/JPEG image upsampled per texel through the sRGB sigmoid table. Beyond the
  // wavelengths its data covers, extrapolate="hold" holds its ends; otherwise it is 0 there,
  // and a render tracing beyond them warns unless extrapolate="zero" was chosen.
  std::shared_ptr<const ReflectanceTexture> texture(const SpectrumDesc& d) const {
    const bool hold = d.extrapolate == SpectrumDesc::Extrapolation::Hold;
    std::shared_ptr<const ReflectanceTexture> t;
    if (d.texels) { // numbers from Python, checked there; their digest joins the render key
      const SpectralTexels& x = *d.texels;
      refs_.fold(std::to_string(x.digest), "texture given as numbers");
      t = ReflectanceTexture::spectralImage(x.width, x.height, x.nm, x.values, hold);
    } else if (d.texture == "colorchecker") {
      t = ReflectanceTexture::colorChecker(hold);
    } else {
      try {
        const std::string bytes = refs_.readFile(d.texture, kMaxTextureFileBytes, "texture file");
        t = readReflectanceTexture(d.texture, bytes, hold);
      } catch (const Error& e) {
        // Every texture error names the texture, whichever reader raised it.
        const std::string what = e.what();
        throw Error(d.loc.str() + ": " + (what.rfind(d.texture, 0) == 0 ? "" : d.texture + ": ") +
                    what);
      }
    }
    if (const auto range = t->dataRangeNm();
        range && d.extrapolate == SpectrumDesc::Extrapolation::Unset)
      refs_.noteTable({d.loc.str(),
                       "texture " + (d.texels ? std::string("given as numbers") : d.texture),
                       range->first, range->second, ""});
    return t;
  }

  IorModel iorModel(const IorDesc& d) const {
    IorModel m;
    switch (d.kind) {
    case IorDesc::Kind::Number:
      m = IorModel::constant(d.value);
      break;
    case IorDesc::Kind::Named:
      if (!namedGlass(d.name.c_str(), m))
        throw Error(d.loc.str() + ": expected a named glass bk7, diamond or fused_silica, found '" +
                    d.name + "'");
      break;
    case IorDesc::Kind::Cauchy:
      m.kind = IorModel::Kind::Cauchy;
      m.c = {d.coefficients[0],
             d.coefficients[1],
             d.coefficients.size() > 2 ? d.coefficients[2] : 0.0,
             0,
             0,
             0};
      break;
    case IorDesc::Kind::Sellmeier:
      m.kind = IorModel::Kind::Sellmeier;
      for (size_t i = 0; i < 6; ++i) m.c[i] = d.coefficients[i];
      break;
    }
    if (const auto nm = iorOutsideRange(m, kTraceMinNm, kTraceMaxNm, 1.0, 10.0))
      throw Error(d.loc.str() + ": expected an index of refraction within [1, 10] over " +
                  tracedRange() + ", found " +
                  (std::isfinite(m.at(*nm)) ? numberText(m.at(*nm))
                                            : std::string("no finite real index (a pole of the "
                                                          "formula, or n^2 < 0)")) +
                  " at " + numberText(*nm) + " nm");
    return m;
  }

  // An instrument EEM made an absolute Donaldson matrix (spectra/eem_import.h); what the
  // import did is said in a note.
  std::shared_ptr<const ReradiationMatrix> importedEem(const FluorescenceDesc& f,
                                                       const Spectrum* rho) const {
    const EemDesc& e = *f.eem;
    auto table = [&](const std::string& path, EemSummary& counts) {
      return withoutScatter(
          parseEemCsv(refs_.readFile(path, 64u << 20, "EEM file"), path, e.layout), e.layout,
          counts);
    };
    EemSummary summary, referenceCounts; // the note reports the sample's
    const EemTable sample = table(e.file, summary);
    std::optional<EemTable> reference;
    EemYield yield;
    yield.quantumYield = f.quantumYield;
    if (!e.referenceFile.empty()) {
      reference = table(e.referenceFile, referenceCounts);
      yield.reference = &*reference;
      yield.referenceYield = e.referenceYield;
      yield.referenceAbsorptance = e.referenceAbsorptance;
      yield.referenceExcitationNm = e.referenceExcitationNm;
    }
    // What the loader requires, checked again for scenes built otherwise (Python edits).
    if (!f.quantumYield && e.referenceFile.empty())
      throw Error(f.loc.str() + ": expected <yield> or <reference> with an <eem>, found neither");
    if (!f.peakAbsorptance && !e.absorptance)
      throw Error(f.loc.str() + ": expected <peak> or <absorptance> with an <eem>, found neither");
    EemAbsorptance absorptance;
    std::optional<Spectrum> a;
    if (e.absorptance) {
      a = refs_.resolve(*e.absorptance, SpectrumRole::Reflectance);
      for (double nm : sample.excitationNm)
        if (!((*a)(nm) >= 0 && (*a)(nm) <= 1))
          throw Error(e.absorptance->loc.str() +
                      ": expected an absorptance within [0, 1] at "
                      "the EEM's excitation wavelengths, found " +
                      numberText((*a)(nm)) + " at " + numberText(nm) + " nm");
      absorptance.spectrum = [&a](double nm) { return (*a)(nm); };
    } else {
      absorptance.peak = f.peakAbsorptance;
    }
    MeasuredMatrix m = donaldsonFromEem(sample, e.layout, yield, absorptance, summary);
    // The emission profile (counts summed over excitation): how much is left at each end.
    {
      const size_t rows = sample.excitationNm.size(), cols = sample.emissionNm.size();
      std::vector<double> profile(cols, 0.0);
      for (size_t r = 0; r < rows; ++r)
        for (size_t c = 0; c < cols; ++c) profile[c] += std::max(0.0, sample.counts[r * cols + c]);
      const double peak = *std::max_element(profile.begin(), profile.end());
      if (peak > 0)
        emissionWindows_.push_back({e.loc.str(),
                                    e.file,
                                    sample.emissionNm.front(),
                                    sample.emissionNm.back(),
                                    profile.front() / peak,
                                    profile.back() / peak,
                                    {}});
    }
    auto r = std::make_shared<const ReradiationMatrix>(ReradiationMatrix::fromMeasured(m, rho));
    if (!emissionWindows_.empty() && emissionWindows_.back().where == e.loc.str())
      emissionWindows_.back().photonsPerBin = emittedPhotonsPerBin(*r);
    if (summary.modelledFraction < kEemWarnModelledFraction)
      warnings_.push_back(e.loc.str() + ": warning: the EEM " + e.file +
                          " is mostly outside what the matrix models: " + summary.coverageText() +
                          " (the dye's light there is missing from the render)");
    warnings_.push_back(
        e.loc.str() + ": note: the EEM " + e.file + " imported (" + summary.text() +
        "); absorptance " +
        (e.absorptance ? "as given"
                       : "from its excitation profile, peak " + numberText(*f.peakAbsorptance)) +
        "; its elastic reflectance is the material's");
    return r;
  }

  FluorescenceModel fluorescence(const FluorescenceDesc& f) const {
    FluorescenceModel p;
    // What the loader requires, checked again for scenes built otherwise (Python edits).
    if (!f.stokesNm || (!f.absorptionName && !f.absorptionNm))
      throw Error(f.loc.str() +
                  ": expected <absorption> and <stokes> in a fluorescence model, "
                  "found " +
                  (f.stokesNm ? "no <absorption>" : "no <stokes>"));
    if (f.absorptionName) {
      const auto peak = namedAbsorptionPeak(*f.absorptionName);
      if (!peak)
        throw Error(
            f.loc.str() +
            ": expected an absorption colour (red, orange, yellow, green, blue, purple, uv) "
            "or a wavelength in nm, found '" +
            *f.absorptionName + "'");
      p.absorptionPeakNm = *peak;
    } else {
      p.absorptionPeakNm = *f.absorptionNm;
    }
    p.stokesNm = *f.stokesNm;
    // The matrix grid is the traced range (300-1100 nm): an emission centred beyond it would be
    // renormalised into the grid's last bins, i.e. emitted where the material does not emit.
    const double emissionNm = p.absorptionPeakNm + p.stokesNm;
    if (emissionNm > kTraceMaxNm)
      throw Error(f.loc.str() +
                  ": expected the fluorescence emission (absorption peak + Stokes "
                  "shift) within the traced range " +
                  tracedRange() + ", found " + numberText(emissionNm) + " nm");
    if (f.widthNm) p.widthNm = *f.widthNm;
    if (f.skew) p.skew = *f.skew;
    if (f.quantumYield) p.quantumYield = *f.quantumYield;
    if (f.peakAbsorptance) p.peakAbsorptance = *f.peakAbsorptance;
    return p;
  }

  // The object's emitted radiance, checked again after its scale; a lamp given as measured
  // (irradiance at a distance, or flux) divided by what one unit of radiance of its shape gives.
  std::optional<EmitterSpectrum> emission(const ObjectDesc& o, bool spectral,
                                          const ShapeGeometry& shape) const {
    if (!o.emission) return std::nullopt;
    Spectrum e;
    double perRadiance = 1;
    if (o.emissionAt)
      perRadiance = axialIrradiancePerRadiance(shape, *o.emissionAt, o.emission->loc.str());
    else if (o.emissionFlux)
      perRadiance = fluxPerRadiance(shape, o.emission->loc.str());
    if (!(perRadiance > 0))
      throw Error(o.emission->loc.str() + ": expected an emitter that reaches its measuring " +
                  "point, found none (a zero projected solid angle)");
    if (spectral || o.emission->kind != SpectrumDesc::Kind::Number) {
      const Spectrum written = refs_.resolve(*o.emission, SpectrumRole::Emission);
      const double factor = o.emissionScale / perRadiance;
      SceneReferences::checkEmission(written.scaled(factor), o.emission->loc);
      return EmitterSpectrum{written, factor};
    } else {
      // rt and mcpt: a numeric <emission> is scaled by <color> (white if absent); a spectrum
      // is used as in spectral mode.
      const double k = o.emission->number * o.emissionScale / perRadiance;
      const auto* color = o.params.get<std::array<double, 4>>("color");
      const Rgb c = color ? Rgb{(*color)[0] * k, (*color)[1] * k, (*color)[2] * k} : Rgb{k, k, k};
      try {
        e = upsampleSrgbIlluminant(c);
      } catch (const Error& err) {
        throw Error(o.emission->loc.str() + ": " + err.what());
      }
    }
    SceneReferences::checkEmission(e, o.emission->loc);
    return EmitterSpectrum{e, 1.0};
  }

  // What an emitter of spectrum `shape` (as written in the scene) times `factor` traces:
  // forRendering(shape.scaled(factor)); in a relightable build the factor alone (flat), the
  // shape kept for its relight source (set in `source`).
  Spectrum traced(const Spectrum& shape, double factor, uint16_t group, const SourceLocation& loc,
                  RenderScene& scene, uint16_t& source) const {
    source = 0;
    if (!desc_.relightable) return forRendering(shape.scaled(factor));
    source = relightSource(forRendering(shape), group, loc, scene);
    return Spectrum(ConstantSpectrum{1.0}, factor);
  }

  // The relight source of an emitter of light group `group` with spectrum `shape` in a
  // relightable build: the group's source of the same spectrum (equal at every nm of the traced
  // range, to 1e-6), or a new one.
  static uint16_t relightSource(const Spectrum& shape, uint16_t group, const SourceLocation& loc,
                                RenderScene& scene) {
    RelightSpectra& r = scene.relight;
    for (size_t s = 0; s < r.ofSource.size(); ++s) {
      if (r.groupOfSource[s] != group) continue;
      bool same = true;
      for (int nm = static_cast<int>(kTraceMinNm); same && nm <= static_cast<int>(kTraceMaxNm);
           ++nm) {
        const double a = shape(nm), b = r.ofSource[s](nm);
        same = std::abs(a - b) <= 1e-6 * std::max(std::abs(a), std::abs(b));
      }
      if (same) return static_cast<uint16_t>(s);
    }
    if (r.ofSource.size() >= 4096)
      throw Error(loc.str() + ": --relightable: expected at most 4096 emission spectra to relight, "
                              "found more");
    r.ofSource.push_back(shape);
    r.groupOfSource.push_back(group);
    return static_cast<uint16_t>(r.ofSource.size() - 1);
  }

  const SceneDesc& desc_;
  mutable SceneReferences refs_;              ///< spectra resolved, referenced files in the digest
  mutable std::vector<std::string> warnings_; ///< the kinds' builds' warnings
  std::map<std::string, uint32_t> materialByText_;      ///< a description's material index
  std::vector<uint32_t> materialIdOf_;                  ///< per material index: its MaterialId
  mutable std::vector<EmissionWindow> emissionWindows_; ///< imported EEMs' emission windows
  const MediumKindInputs mediumInputs_;                 ///< what the media kinds ask of the scene
};

} // namespace

RenderScene buildRenderScene(const SceneDesc& desc) {
  return Builder(desc).build(true);
}

RenderScene resolveRenderScene(const SceneDesc& desc) {
  return Builder(desc).build(false);
}

std::vector<std::string> extrapolationWarnings(const RenderScene& scene, double loNm, double hiNm) {
  std::vector<std::string> out;
  for (const TabulatedRange& t : scene.tables) {
    if (t.loNm <= loNm && t.hiNm >= hiNm) continue;
    std::string w = t.where + ": warning: spectrum '" + t.what + "' is tabulated over " +
                    numberText(t.loNm) + "-" + numberText(t.hiNm) + " nm and this render traces " +
                    numberText(loNm) + "-" + numberText(hiNm) + " nm: it is 0 beyond its table (" +
                    (t.choice.empty() ? std::string("write extrapolate=\"zero\" or "
                                                    "extrapolate=\"hold\" on the element")
                                      : t.choice) +
                    " to choose)";
    if (std::find(out.begin(), out.end(), w) == out.end()) out.push_back(std::move(w));
  }
  for (const EmissionWindow& w : scene.emissionWindows) {
    // Most of the dye's photons beyond the traced range: its light is not in the image.
    double inside = 0, total = 0;
    for (int o = 0; o < static_cast<int>(w.photonsPerBin.size()); ++o) {
      total += w.photonsPerBin[static_cast<size_t>(o)];
      const double nm = ReradiationMatrix::centre(o);
      if (nm >= loNm && nm <= hiNm) inside += w.photonsPerBin[static_cast<size_t>(o)];
    }
    if (total > 0 && inside < 0.5 * total) {
      char pct[32];
      std::snprintf(pct, sizeof pct, "%.3g%%", 100 * (1 - inside / total));
      out.push_back(w.where + ": warning: the EEM " + w.file + " emits " + pct +
                    " of its modelled photons outside the " + numberText(loNm) + "-" +
                    numberText(hiNm) +
                    " nm this render traces (that light is not in the image: "
                    "render bands that cover the dye's emission)");
    }
    for (const bool high : {false, true}) {
      const double end = high ? w.hiNm : w.loNm, share = high ? w.shareAtHi : w.shareAtLo;
      if ((high ? end >= hiNm : end <= loNm) || share <= kEmissionWindowEdgeShare) continue;
      char pct[32];
      std::snprintf(pct, sizeof pct, "%.3g%%", 100 * share);
      out.push_back(w.where + ": warning: the EEM " + w.file + " measures emission over " +
                    numberText(w.loNm) + "-" + numberText(w.hiNm) + " nm and this render traces " +
                    numberText(loNm) + "-" + numberText(hiNm) + " nm: at " + numberText(end) +
                    " nm its emission is still " + pct + " of its peak, and the matrix is 0 " +
                    (high ? "beyond" : "below") +
                    " it (the dye's light there is missing: measure a wider emission window)");
    }
  }
  return out;
}

} // namespace nx

#pragma once
// A scene as written in a scene file: plain data, every item with its file and line.
// Nothing here is resolved (names stay names); buildRenderScene (integrators/render_scene.h)
// does that.

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "core/params/parameter_set.h"
#include "core/params/scene_values.h"
#include "core/vec3.h"
#include "io/scene_tree.h"
#include "spectra/sensor.h"
#include "spectra/spectrum.h"

namespace nx {

/// The three rendering modes of Niixtracer scene files.
enum class RenderMode { Rt, Mcpt, SpectralMcpt };

/// "rt", "mcpt" or "spectral_mcpt": a mode as <mode> writes it.
inline const char* renderModeName(RenderMode m) {
  return m == RenderMode::Rt ? "rt" : m == RenderMode::Mcpt ? "mcpt" : "spectral_mcpt";
}

/// The mode <mode> names, or nullopt.
inline std::optional<RenderMode> parseRenderMode(const std::string& name) {
  for (RenderMode m : {RenderMode::Rt, RenderMode::Mcpt, RenderMode::SpectralMcpt})
    if (name == renderModeName(m)) return m;
  return std::nullopt;
}

/// <spectrum name="...">: a spectrum defined once and used by name.
struct NamedSpectrumDesc {
  std::string name;
  SpectrumDesc spectrum;
  SourceLocation loc;
};

/// <medium type="..."> inside a sphere or closed mesh: a medium kind (homogeneous when absent)
/// and its parameters as written (integrators/media/medium_kinds.h, docs/reference/media.md).
struct MediumDesc {
  std::string kind = "homogeneous";
  ParameterSet params; ///< <sigma_a> (its scale="..." as sigma_a_scale), <sigma_s>, <g>, ...
  SourceLocation loc;
};

/// How a surface scatters: a material kind with its parameters (inline on an object, or a
/// top-level <material id="..." type="...">). Which parameters a kind takes, their defaults and
/// meaning: its schema (integrators/materials/material_kind.h, docs/reference/materials.md).
struct MaterialDesc {
  std::string material; ///< the kind (matte, glass, ...), or the id of a <material id>
  SourceLocation materialLoc;
  ParameterSet params; ///< <color>, <reflectance>, <roughness>, ... as written
};

/// <material id="..." type="...">: a material defined once and used by objects by its id.
struct NamedMaterialDesc {
  std::string id;
  MaterialDesc material;
  SourceLocation loc;
};

/// An object: a shape kind (sphere, plane, triangle, quad, mesh) with its parameters, and its
/// appearance: its own material (the MaterialDesc part) or a reference to a <material id>.
/// Which parameters a shape kind takes: its schema (accel/shape_kinds.h,
/// docs/reference/shapes.md).
struct ObjectDesc : MaterialDesc {
  std::string shape = "sphere"; ///< the kind, as its element name
  std::string name;             ///< its name="..." (regions of a comparison), or empty
  ParameterSet geometry;        ///< <center>, <radius>, ... (file="..." of a mesh) as written
  SourceLocation loc;
  std::string materialRef;              ///< the id of a <material id> (then no inline material)
  std::optional<SpectrumDesc> emission; ///< absent, 0 or empty: not a light
  double emissionScale = 1;             ///< <emission scale="...">
  /// <emission at="d">: the spectrum is the irradiance on the emitter's axis at distance d
  std::optional<double> emissionAt;
  bool emissionFlux = false;        ///< <emission quantity="flux">: the spectrum is the total flux
  std::optional<MediumDesc> medium; ///< the medium filling a sphere or closed mesh, if any
  std::string group; ///< its group="NAME" (light groups: its emission's layer), or empty
};

/// A <light type="...">: a light kind (point by default, Niixtracer's) and its parameters as
/// written (integrators/lights/light_kinds.h, docs/reference/lights.md).
struct LightDesc {
  std::string kind = "point";
  ParameterSet params; ///< <position>, <color>, <emission> (its scale="..." as emission_scale), ...
  SourceLocation loc;
  std::string group; ///< its group="NAME" (light groups), or empty
};

/// The pinhole camera.
struct CameraDesc {
  Vec3d position, lookAt;
  Vec3d up{0, 1, 0};
  double fovDegrees = 81.8; ///< horizontal; the thesis-era default
  /// OpenCV calibration (nxrender extension): fx, fy, cx, cy in pixels of the xres x yres image
  std::optional<std::array<double, 4>> intrinsics;
  /// r11 .. r33, t1, t2, t3: x_cam = R x_world + t (replaces position/look_at/up)
  std::optional<std::array<double, 12>> extrinsics;
  std::array<double, 5> distortion{}; ///< k1, k2, p1, p2, k3 (OpenCV's order; zero if absent)
  /// <thin_lens>aperture radius, focus distance</thin_lens> (scene units), if any
  std::optional<std::array<double, 2>> thinLens;
  /// calibration="file" (an OpenCV FileStorage YAML or XML) the intrinsics, distortion and pose
  /// came from, if any, and the image size it states (the render's must equal it)
  std::string calibrationFile;
  std::optional<std::array<int, 2>> calibrationSize;
  uint64_t calibrationDigest = 0; ///< the file's bytes (FNV-1a), part of the render key
  SourceLocation loc, distortionLoc;
};

/// <settings>.
struct SettingsDesc {
  int width = 0, height = 0;
  std::string outputPath; ///< as written; empty if absent
  RenderMode mode = RenderMode::SpectralMcpt;
  int depth = 5;
  int samples = 16;
  std::optional<SpectrumDesc> illuminant; ///< <illum>
  Sensor bands;
  /// <sensor csv="..." centres="...">: the measured responses' file and nominal centres as
  /// written (empty when the sensor is not a file's); to_text writes them back
  std::string sensorFile, sensorCentres;
  std::optional<SpectrumDesc> background; ///< uniform environment radiance
  std::string backgroundGroup;            ///< <background group="NAME">, or empty
  uint32_t seed = 0;
  SourceLocation loc, widthLoc, modeLoc;
};

/// A relighting target (--relight-for [GROUP=]SPEC, relight_for=): a spectrum the emitters of a
/// light group will be relit to.
struct RelightTargetDesc {
  std::string group;  ///< the light group; empty: every group
  Spectrum spectrum;  ///< the spectrum, as an <emission> would give it
  std::string source; ///< what it came from (a file or a name), for messages
  /// How it was given, for messages: the option ("--relight-for" or Python's "relight_for") and
  /// the target itself ("--relight-for led=LED450.csv", "relight_for['led'][1]")
  std::string option = "--relight-for", where = "--relight-for";
};

/// Everything a scene file says.
struct SceneDesc {
  std::string file; ///< the scene file as given
  /// FNV-1a of the scene's state (sceneStateText), then of the referenced files' bytes as the
  /// build reads them: the render key's scene part
  uint64_t textDigest = 0;
  SettingsDesc settings;
  CameraDesc camera;
  std::vector<LightDesc> lights;
  std::vector<ObjectDesc> objects;
  std::vector<NamedSpectrumDesc> spectra;
  std::vector<NamedMaterialDesc> materials; ///< top-level <material id="...">
  std::vector<std::string> warnings;        ///< "file:line: ..." notes that are not errors
  /// Build for a relightable render (--relightable; never read from the file): every emitter
  /// traced as its factor times a flat unit spectrum, its own spectrum kept per light group.
  bool relightable = false;
  /// The spectra a relightable render will be relit to (--relight-for, relight_for=; never
  /// read from the file): its excitation and light choices are drawn for them
  std::vector<RelightTargetDesc> relightTargets;
};

class SceneKindSchemas; // io/scene_kind_schemas.h

/// Reads a scene file, its kinds' parameters by `kinds` (integrators/scene_reader.h gives
/// the registered ones and the forms without it). Throws nx::Error "file:line: expected ..., found
/// ..." on any problem: XML syntax, unknown or repeated tags and attributes, missing required tags,
/// malformed, non-finite or out-of-range numbers, unknown material or mode names, resolutions whose
/// buffers would not fit in memory.
SceneDesc loadScene(const std::string& path, const SceneKindSchemas& kinds);

/// Bytes the film and the output image of a width x height render with `bands` bands take
/// (what the memory checks compare with the memory budget).
double renderBufferBytes(int width, int height, int bands);

/// Reads a scene given as data (io/scene_tree.h) exactly as its scene text: errors name the
/// path in the data ("objects[2].faces: ...") instead of a line; `name` is the scene's name
/// and anchors relative file names (its directory; "" or "<dict>": the working directory).
SceneDesc parseSceneTree(const SceneTree& tree, const std::string& name,
                         const SceneKindSchemas& kinds);

/// One object (light false) or light given as data (Scene.objects.append(dict)), checked as
/// in a scene file: errors name `path` ("objects[3].radius: ..."); an object's material may
/// be one of `scene`'s named materials; relative file names are relative to the working
/// directory (as sceneToTree gives them for a scene read from there).
std::variant<ObjectDesc, LightDesc> parseItemTree(const SceneTree& item, bool light,
                                                  const std::string& path, const SceneDesc& scene,
                                                  const SceneKindSchemas& kinds);

/// Removes the fluorescence of every object and named material (--no-fluorescence).
void removeFluorescence(SceneDesc& desc);

/// Parses scene text; `file` names it in messages and anchors relative paths.
SceneDesc parseScene(const std::string& text, const std::string& file,
                     const SceneKindSchemas& kinds);

} // namespace nx

#pragma once
// A scene as written in a scene file: plain data, every item with its file and line.
// Nothing here is resolved (names stay names); buildRenderScene (integrators/render_scene.h)
// does that.

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/vec3.h"
#include "io/parameter_set.h"
#include "io/scene_values.h"
#include "spectra/sensor.h"

namespace nx {

/// The three rendering modes of Niixtracer scene files.
enum class RenderMode { Rt, Mcpt, SpectralMcpt };

/// <spectrum name="...">: a spectrum defined once and used by name.
struct NamedSpectrumDesc {
  std::string name;
  SpectrumDesc spectrum;
  SourceLocation loc;
};

/// <medium> inside a closed object: a homogeneous participating medium filling it.
struct MediumDesc {
  SpectrumDesc sigmaA;                     ///< absorption coefficient per scene unit of length
  SpectrumDesc sigmaS;                     ///< scattering coefficient per scene unit of length
  double sigmaAScale = 1, sigmaSScale = 1; ///< their scale="..." factors (unit conversions)
  double g = 0;                            ///< Henyey-Greenstein mean cosine, in (-1, 1)
  /// Emitted radiance Le (source sigma_a Le), with its scale="..."
  std::optional<SpectrumDesc> emission;
  double emissionScale = 1; ///< <emission scale="..."> of the medium
  /// A fluorescent dye dissolved in it: the parametric model, its <peak> being the dye's peak
  /// absorption coefficient per unit length (added to sigma_a's absorption)
  std::optional<FluorescenceDesc> fluorescence;
  SourceLocation loc;
};

/// The shapes a scene can hold.
enum class ShapeType { Sphere, Plane, Triangle, Quad, Mesh };

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

/// An affine map p -> m p + t (row-major m), composed from a <transform>'s steps.
struct AffineDesc {
  std::array<std::array<double, 3>, 3> m{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
  Vec3d t;
};

/// A sphere, plane, triangle, quad or mesh file with its appearance: its own material (the
/// MaterialDesc part) or a reference to a <material id>.
struct ObjectDesc : MaterialDesc {
  ShapeType shape = ShapeType::Sphere;
  SourceLocation loc;
  Vec3d center;                         ///< sphere
  double radius = 0;                    ///< sphere
  Vec3d normal;                         ///< plane (unit length after loading)
  double distance = 0;                  ///< plane: dot(normal, p) = distance
  std::array<Vec3d, 3> vertices;        ///< triangle vA, vB, vC; quad: origin, edge u, edge v
  std::string meshPath;                 ///< mesh: the file, resolved relative to the scene file
  AffineDesc transform;                 ///< mesh: applied to its vertices
  std::string materialRef;              ///< the id of a <material id> (then no inline material)
  std::optional<SpectrumDesc> emission; ///< absent, 0 or empty: not a light
  double emissionScale = 1;             ///< <emission scale="...">
  std::optional<MediumDesc> medium;     ///< the medium filling a sphere, if any
};

/// A <light type="...">: a light kind (point by default, Niixtracer's) and its parameters as
/// written (integrators/lights/light_kinds.h, docs/reference/lights.md).
struct LightDesc {
  std::string kind = "point";
  ParameterSet params; ///< <position>, <color>, <emission> (its scale="..." as emission_scale), ...
  SourceLocation loc;
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
  std::optional<SpectrumDesc> background; ///< uniform environment radiance
  uint32_t seed = 0;
  SourceLocation loc, widthLoc, modeLoc;
};

/// Everything a scene file says.
struct SceneDesc {
  std::string file; ///< the scene file as given
  uint64_t textDigest =
      0; ///< FNV-1a of the scene text (with the referenced files' bytes, the render key)
  SettingsDesc settings;
  CameraDesc camera;
  std::vector<LightDesc> lights;
  std::vector<ObjectDesc> objects;
  std::vector<NamedSpectrumDesc> spectra;
  std::vector<NamedMaterialDesc> materials; ///< top-level <material id="...">
  std::vector<std::string> warnings;        ///< "file:line: ..." notes that are not errors
};

/// Reads a scene file. Throws nx::Error "file:line: expected ..., found ..." on any problem:
/// XML syntax, unknown or repeated tags and attributes, missing required tags, malformed,
/// non-finite or out-of-range numbers, unknown material or mode names, resolutions whose
/// buffers would not fit in memory.
SceneDesc loadScene(const std::string& path);

/// Bytes the film and the output image of a width x height render with `bands` bands take
/// (what the memory checks compare with the memory budget).
double renderBufferBytes(int width, int height, int bands);

/// Parses scene text; `file` names it in messages and anchors relative paths.
SceneDesc parseScene(const std::string& text, const std::string& file);

} // namespace nx

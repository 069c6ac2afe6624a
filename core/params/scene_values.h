#pragma once
// The values a scene's parameters take, as written: spectra, indices of refraction,
// fluorescence, coatings, each with the file and line it came from.

#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/hash.h"
#include "core/params/concentration_map.h"
#include "core/params/eem_layout.h"
#include "core/vec3.h"

namespace nx {

struct MeasuredMatrix; // spectra/reradiation_matrix.h

/// A spectral reflectance texture given as numbers (from Python) rather than a file: width x
/// height texels (row 0 at the top), values [texel][band] in [0, 1] at increasing band
/// wavelengths, and a digest of the content (its identity in the render key).
struct SpectralTexels {
  int width = 0, height = 0;
  std::vector<double> nm;
  std::vector<float> values;
  uint64_t digest = 0;
};

/// The digest of a texture's size, wavelengths and values (SpectralTexels::digest).
inline uint64_t spectralTexelsDigest(const SpectralTexels& t) {
  uint64_t h = fnv1a64(std::to_string(t.width) + "x" + std::to_string(t.height));
  h = fnv1a64(
      std::string_view(reinterpret_cast<const char*>(t.nm.data()), t.nm.size() * sizeof(double)),
      h);
  return fnv1a64(std::string_view(reinterpret_cast<const char*>(t.values.data()),
                                  t.values.size() * sizeof(float)),
                 h);
}

/// Rows of numbers written inline (a mesh's <vertices>, <faces>, <normals>, <uv>), `columns`
/// per row: real numbers kept as float (the precision meshes are kept in) or indices as
/// uint32. Shared, so copies of a description share the numbers.
struct ArrayDesc {
  std::shared_ptr<const std::vector<float>> reals;      ///< ParamType::Reals, else null
  std::shared_ptr<const std::vector<uint32_t>> indices; ///< ParamType::Indices, else null
  uint32_t columns = 3;
  uint64_t digest = 0; ///< FNV-1a of the numbers' bytes: their identity in the render key
  /// Number of rows.
  size_t rows() const {
    return (reals ? reals->size() : indices ? indices->size() : 0) / (columns ? columns : 1);
  }
};

/// Where an item was written: file name and 1-based line, or its path in a scene given as data.
struct SourceLocation {
  std::string file;
  int line = 0;
  /// "file:line", the prefix of every error about this item; for an item given as data
  /// (line 0), its path in the data ("objects[2].radius").
  std::string str() const { return line > 0 ? file + ":" + std::to_string(line) : file; }
};

/// A spectrum as a scene refers to it.
struct SpectrumDesc {
  enum class Kind { Name, Number, Pairs, CsvFile, Texture };
  /// What a table does beyond its wavelengths (extrapolate="zero|hold"; unset: zero, with a
  /// warning when the render traces beyond it).
  enum class Extrapolation { Unset, Zero, Hold };
  Kind kind = Kind::Number;
  Extrapolation extrapolate = Extrapolation::Unset;
  /// negative="clamp": a measured table's negative values (dark-subtraction noise) set to 0,
  /// their count warned about; else a negative value is refused where it cannot be
  bool clampNegative = false;
  std::string name;          ///< Kind::Name: a built-in or scene-defined spectrum name
  double number = 0;         ///< Kind::Number: a flat spectrum
  std::vector<double> nm;    ///< Kind::Pairs: wavelengths
  std::vector<double> value; ///< Kind::Pairs: values
  std::string path;          ///< Kind::CsvFile: resolved relative to the scene file
  std::string column;        ///< Kind::CsvFile: the header's name of the value column, or ""
  std::string texture; ///< Kind::Texture: "colorchecker" or a spectral EXR (relative to the scene)
  /// Kind::Texture given as numbers (then `texture` is empty), checked
  std::shared_ptr<const SpectralTexels> texels;
  SourceLocation loc;
};

/// Index of refraction: a number, a built-in glass, or a dispersion formula.
struct IorDesc {
  enum class Kind { Number, Named, Cauchy, Sellmeier };
  Kind kind = Kind::Number;
  double value = 1.5;               ///< Kind::Number
  std::string name;                 ///< Kind::Named (bk7, diamond, fused_silica)
  std::vector<double> coefficients; ///< Cauchy: A, B[, C] (um); Sellmeier: B1 B2 B3 C1 C2 C3 (um^2)
  SourceLocation loc;
};

/// <fluorescence><eem .../>: an instrument excitation-emission matrix to import, with what
/// makes it absolute (the <fluorescence>'s <yield> or <reference>, <peak> or <absorptance>).
struct EemDesc {
  std::string file;                        ///< the EEM CSV
  EemLayout layout;                        ///< its orientation, units and scatter bands
  std::optional<SpectrumDesc> absorptance; ///< A(lambda), or none: from the excitation profile
  std::string referenceFile;               ///< a reference dye's EEM (the relative yield), or ""
  double referenceYield = 0, referenceAbsorptance = 0; ///< its yield and absorptance
  std::optional<double> referenceExcitationNm; ///< where the two are compared (default: peak)
  SourceLocation loc;
};

/// <fluorescence>: the parameters of the re-radiation matrix, or a measured matrix.
/// A dye as a datasheet gives it (<fluorescence> with <absorptance> and <emission>): its
/// absorptance spectrum a(lambda) (on a surface, in [0, 1]; a medium's dye: its shape, scaled to
/// the medium's <peak> coefficient at its maximum) and its emission spectrum (photons, any
/// scale); with the quantum yield, the separable matrix (ReradiationMatrix::fromSpectra).
struct DyeSpectra {
  SpectrumDesc absorptance, emission;
};

struct FluorescenceDesc {
  std::optional<std::string> absorptionName; ///< a colour name (peak wavelength)
  std::optional<double> absorptionNm;        ///< or the peak wavelength itself
  std::optional<double> stokesNm;
  std::optional<double> widthNm, skew, quantumYield, peakAbsorptance;
  std::optional<std::string> matrixCsv; ///< measured Donaldson matrix
  /// Or the measured matrix itself (given from Python as arrays), checked
  std::shared_ptr<const MeasuredMatrix> matrix;
  uint64_t matrixDigest = 0; ///< the content of `matrix` (measuredMatrixDigest), set with it
  /// Or an instrument EEM (quantumYield and peakAbsorptance are then its yield and a_max)
  std::shared_ptr<const EemDesc> eem;
  /// Or the separable form: absorptance and emission spectra (quantumYield: the yield;
  /// peakAbsorptance: a medium's peak coefficient)
  std::shared_ptr<const DyeSpectra> spectra;
  /// A surface dye's relative concentration over the surface (<concentration>FILE</...>, a CSV
  /// grid), scaling its absorptance per place (core/params/concentration_map.h); or the map itself
  /// (given from Python as numbers)
  std::optional<std::string> concentrationCsv;
  std::shared_ptr<const ConcentrationMap> concentration;
  SourceLocation loc;
};

/// A thin-film coating: thickness in nm and index of refraction.
struct CoatingDesc {
  double thicknessNm = 0;
  IorDesc ior;
  SourceLocation loc;
};

/// An affine map p -> m p + t (row-major m): a mesh's <transform>, its steps composed.
struct AffineDesc {
  std::array<std::array<double, 3>, 3> m{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
  Vec3d t;
  /// det(m): a transform must keep volume (non-zero and finite).
  double determinant() const {
    return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
           m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
           m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  }
  /// Whether it keeps volume: |det| > 1e-300 and finite (a singular map flattens the mesh).
  bool keepsVolume() const {
    const double d = determinant();
    return std::isfinite(d) && std::abs(d) > 1e-300;
  }
};

} // namespace nx

#pragma once
// A precomputed table of sigmoid-polynomial coefficients over the RGB cube, looked up with
// trilinear interpolation (Jakob & Hanika 2019, section 4): RGB upsampling without a fit per
// colour, fast enough for every texel of an image.

#include <functional>
#include <string>
#include <vector>

#include "spectra/sigmoid_fit.h"

namespace nx {

/// Coefficients of sigmoid-polynomial reflectances on a grid over linear sRGB in [0, 1]^3.
/// For each largest channel l (0, 1, 2) the grid runs over z = that channel's value (at
/// smoothstep(smoothstep(k / (res - 1))), dense near 0 and 1) and the other two channels
/// divided by z, x = rgb[(l + 1) % 3] / z and y = rgb[(l + 2) % 3] / z, uniformly in [0, 1].
class SigmoidTable {
public:
  /// A table of the given resolution from its z positions (res values) and coefficients
  /// (3 * res^3 entries of 3 floats, ordered [l][k][j][i][c], i the x index).
  SigmoidTable(int resolution, std::vector<float> zPositions, std::vector<float> coefficients);

  /// The z positions of a table of this resolution.
  static std::vector<float> zPositions(int resolution);

  /// Runs body(0) ... body(count - 1), in any order (possibly in parallel).
  using ForEach = std::function<void(int count, const std::function<void(int)>& body)>;

  /// Fits every entry of a table of the given resolution (3 * res^3 * 3 floats, ordered as
  /// the constructor takes them). Continuation as in the paper: the slice at z = 1/2 is
  /// walked outward from its grey entry, each fit starting at its neighbour's solution; then
  /// each (l, x, y) line is walked from there toward z = 0 and z = 1. `forEach` may run the
  /// independent pieces in parallel.
  static std::vector<float> fit(int resolution, const ForEach& forEach);

  /// The table in its binary form: "NXSIGTAB", the resolution (int32), the z positions and
  /// the coefficients (float32), all little-endian as on the machines this builds for.
  std::string toBytes() const;
  /// A table from toBytes()'s form; throws std::invalid_argument if it is not one.
  static SigmoidTable fromBytes(const unsigned char* bytes, size_t size);

  /// Interpolated coefficients for a linear sRGB colour with channels in [0, 1].
  SigmoidCoefficients lookup(const Rgb& linearSrgb) const;

  /// Grid points per axis.
  int resolution() const { return res_; }

private:
  int res_;
  std::vector<float> z_;
  std::vector<float> data_;
};

/// The built-in sRGB table (fitted at build time by nx_generate_sigmoid_table; in the
/// nx_spectra_rgb library).
const SigmoidTable& srgbSigmoidTable();

} // namespace nx

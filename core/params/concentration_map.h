#pragma once
// A map of a surface dye's relative concentration over the surface (docs/inverse.md): a grid of
// values in [0, 1], each scaling the dye's absorptance where it lies (so its re-radiation, and
// the light it takes from the elastic reflection), looked up bilinearly by the hit's (u, v) as
// reflectance textures are.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace nx {

/// The grid: width x height values in [0, 1], row 0 at the top (v = 1).
struct ConcentrationMap {
  int width = 0, height = 0;
  std::vector<float> values; ///< [row * width + column]
  uint64_t digest = 0;       ///< of the size and values (the render key)

  /// The four values around (u, v) (texel centres at (i + 1/2) / width, edges clamped) and
  /// their bilinear weights.
  void bilinear(float u, float v, size_t (&index)[4], float (&weight)[4]) const;
  /// The concentration at (u, v).
  float at(float u, float v) const {
    size_t i[4];
    float w[4];
    bilinear(u, v, i, w);
    return w[0] * values[i[0]] + w[1] * values[i[1]] + w[2] * values[i[2]] + w[3] * values[i[3]];
  }
};

/// A map from numbers (row 0 at the top), checked: at least one value, each finite and in
/// [0, 1]. Throws nx::Error "<where>: expected ..., found ..." naming the first bad value.
ConcentrationMap makeConcentrationMap(int width, int height, std::vector<float> values,
                                      const std::string& where);

/// A map from a CSV grid: one row of comma-separated values per line (row 0 at the top), every
/// row as long. Errors name source:line.
ConcentrationMap parseConcentrationCsv(const std::string& text, const std::string& source);

} // namespace nx

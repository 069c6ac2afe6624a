#pragma once
// Reflectance that varies over a surface: looked up by the hit's (u, v) for all lanes at once.

#include <algorithm>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include "spectra/sampled_wavelengths.h"
#include "spectra/spectrum.h"

namespace nx {

/// A reflectance texture: a spectral image (bands at their centroid wavelengths, bilinear in
/// space, linear between bands, beyond them the end bands held or 0), an RGB image upsampled per
/// texel, or the built-in ColorChecker chart. (u, v) = (0, 0) is the image's bottom-left corner,
/// (1, 1) its top-right (row 0 of an image is its top); outside [0, 1] the edge texels continue.
class ReflectanceTexture {
public:
  /// A spectral image of width x height texels, `values` [texel][band] (row 0 at the top)
  /// at the given increasing band centroids (nm). Values must lie in [0, 1]. Beyond the first
  /// and last centroid the end bands are held (holdEnds) or the reflectance is 0.
  static std::shared_ptr<const ReflectanceTexture> spectralImage(int width, int height,
                                                                 std::vector<double> centroidsNm,
                                                                 std::vector<float> values,
                                                                 bool holdEnds = false);

  /// An RGB image upsampled per texel: `coefficients` [texel][3] are each texel's
  /// sigmoid-polynomial coefficients (row 0 at the top), bilinear in space between the
  /// texels' spectra.
  static std::shared_ptr<const ReflectanceTexture> sigmoidImage(int width, int height,
                                                                std::vector<float> coefficients);

  /// The ColorChecker Classic, 6 x 4 patches (dark_skin top left at v = 1, black_2 bottom
  /// right), each cell's central kColorCheckerPatchFraction its patch's measured reflectance,
  /// the rest the chart's black frame (reflectance kColorCheckerFrame).
  /// Its patches are measured over 380-780 nm: beyond, held (holdEnds) or 0.
  static std::shared_ptr<const ReflectanceTexture> colorChecker(bool holdEnds = false);

  /// The wavelengths its data covers (nm): an image's first and last centroid, the chart's
  /// measured range; none for an sRGB image (its sigmoid spectra are defined everywhere).
  std::optional<std::pair<double, double>> dataRangeNm() const;

  /// Reflectance at (u, v) for the lanes of lambda.
  SampledSpectrum evaluate(float u, float v, const SampledWavelengths& lambda) const;

  /// Values an image texture holds (texels x bands); 0 for the other kinds.
  size_t valueCount() const { return kind_ == Kind::Image ? values_.size() : 0; }

  /// For an image texture: calls f(index, lane, weight) for each value (index texel * bands +
  /// band, texels row by row from the top) the reflectance at (u, v) depends on at a lane, with
  /// weight d reflectance / d value (bilinear in space, linear between bands, as evaluate).
  template <class F>
  void forEachValueWeight(float u, float v, const SampledWavelengths& lambda, F&& f) const {
    if (kind_ != Kind::Image) return;
    const Bilinear b = bilinear(u, v);
    const size_t bands = centroids_.size();
    for (int i = 0; i < kLanes; ++i) {
      const double nm = lambda.lambda[i];
      const size_t hi = static_cast<size_t>(
          std::upper_bound(centroids_.begin(), centroids_.end(), nm) - centroids_.begin());
      size_t band[2] = {0, 0};
      float w[2] = {0, 0};
      if (nm < centroids_.front() || nm > centroids_.back()) {
        if (!holdEnds_) continue;
        band[0] = hi == 0 ? 0 : bands - 1, w[0] = 1;
      } else if (hi == bands) {
        band[0] = bands - 1, w[0] = 1;
      } else {
        const double t = (nm - centroids_[hi - 1]) / (centroids_[hi] - centroids_[hi - 1]);
        band[0] = hi - 1, w[0] = static_cast<float>(1 - t);
        band[1] = hi, w[1] = static_cast<float>(t);
      }
      for (int k = 0; k < 4; ++k)
        for (int j = 0; j < 2; ++j)
          if (const float weight = b.weight[k] * w[j]; weight != 0)
            f(b.texel[k] * bands + band[j], i, weight);
    }
  }

  /// True when `o` holds the same texels (kind, size, band centroids, values).
  bool sameAs(const ReflectanceTexture& o) const {
    return kind_ == o.kind_ && width_ == o.width_ && height_ == o.height_ &&
           centroids_ == o.centroids_ && values_ == o.values_ && holdEnds_ == o.holdEnds_;
  }

  /// Texels across and down (the chart: 6 x 4).
  int width() const { return width_; }
  int height() const { return height_; }

private:
  enum class Kind : uint8_t { Image, Sigmoid, Chart };
  /// The four texels around (u, v) (indices into the texel grid) and their bilinear weights.
  struct Bilinear {
    size_t texel[4];
    float weight[4];
  };
  Bilinear bilinear(float u, float v) const;
  Kind kind_ = Kind::Image;
  int width_ = 0, height_ = 0;
  std::vector<double> centroids_;
  std::vector<float> values_;
  bool holdEnds_ = false;         ///< beyond the data range: the ends held, else 0
  std::vector<Spectrum> patches_; ///< the chart's patches, with holdEnds_ as their ends
  SampledSpectrum imageAt(float u, float v, const SampledWavelengths& lambda) const;
  SampledSpectrum sigmoidAt(float u, float v, const SampledWavelengths& lambda) const;
  SampledSpectrum chartAt(float u, float v, const SampledWavelengths& lambda) const;
};

/// Share of each ColorChecker cell (per direction) its patch covers; the rest is frame.
inline constexpr float kColorCheckerPatchFraction = 0.85f;
/// Reflectance of the ColorChecker's black frame (flat).
inline constexpr float kColorCheckerFrame = 0.03f;

} // namespace nx

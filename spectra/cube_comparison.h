#pragma once
// Figures comparing a render with a capture band by band and pixel by pixel: per-band RMSE,
// relative RMSE, bias, PSNR and noise z-scores, per-pixel spectral angle, per-region means.

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "spectra/colour.h"
#include "spectra/spectrum.h"

namespace nx {

/// How the render is scaled before it is compared (absolute calibration is often unknown).
enum class ScaleFit {
  None, ///< compared as they are
  /// One factor s minimising sum (capture - s render)^2 over all bands and pixels; with the
  /// render's variances, corrected for the render's noise (errors in the regressor):
  /// s = sum c r / sum (r^2 - var r), since E[r^2] = mu^2 + var r biases the plain fit low.
  Global,
  PerBand, ///< one such factor per band
};

/// A named set of pixels (mask[pixel] != 0).
struct ComparisonRegion {
  std::string name;
  std::vector<uint8_t> mask;
};

/// Two cubes on the same pixels and bands, [pixel][band], and what to compare.
struct ComparisonInputs {
  int width = 0, height = 0, bands = 0;
  int originX = 0, originY = 0;          ///< pixel (0, 0)'s position in the render (for messages)
  std::vector<double> wavelengthNm;      ///< the bands' wavelengths (for reports)
  const float* render = nullptr;         ///< the render's values (resampled to the capture's bands)
  const float* capture = nullptr;        ///< the capture's values
  const float* renderVariance = nullptr; ///< variance of each render value, or null
  /// Variance of each capture value (a render compared as a capture, or a capture with a noise
  /// model), or null: the z-scores then count the render's noise alone
  const float* captureVariance = nullptr;
  std::vector<ComparisonRegion> regions; ///< the regions; none: every pixel
  std::vector<uint8_t> excluded;         ///< [pixel] != 0: left out everywhere (or empty)
};

/// One band's figures over the compared pixels (the union of the regions).
struct BandFigures {
  double wavelengthNm = 0;
  double scale = 1;        ///< factor applied to the render
  double renderMean = 0;   ///< mean of the scaled render
  double captureMean = 0;  ///< mean of the capture
  double bias = 0;         ///< mean of (scaled render - capture)
  double rmse = 0;         ///< root mean square of (scaled render - capture)
  double relativeRmse = 0; ///< rmse / renderMean
  double psnrDb = 0;       ///< 20 log10(largest capture value / rmse); infinite when rmse = 0
  /// bias / its standard error (NaN without render variances): from the render's Monte Carlo
  /// variance and the capture's, when given; with a fitted scale, the delete-a-group
  /// jackknife's over 16 interleaved pixel groups (the scale's own error included). |z| much
  /// above 2-3 says the difference is not noise.
  double zMean = 0;
  /// sqrt(sum d^2 / sum var d) over the pixels, var d = s^2 var r + var c: the pooled ratio of
  /// the differences to their expected noise, about 1 when they are noise alone (pooled, not a
  /// mean of per-pixel ratios: a pixel whose few samples put its variance estimate near 0
  /// would dominate those).
  double rmsZ = 0;
};

/// One region's figures.
struct RegionFigures {
  std::string name;
  long pixels = 0;
  std::vector<double> renderMean, captureMean; ///< per band, scaled render and capture
  double samMeanDeg = 0;                       ///< mean spectral angle over its pixels
  Lab renderLab, captureLab;                   ///< colours of the mean spectra (addRegionColours)
  double deltaE2000 = std::numeric_limits<double>::quiet_NaN(); ///< their CIEDE2000
};

/// Spectral angle statistics (degrees) over the compared pixels where both spectra are
/// non-zero.
struct SamFigures {
  double meanDeg = 0, medianDeg = 0, p95Deg = 0, maxDeg = 0;
  long pixels = 0;          ///< pixels with an angle
  long undefinedPixels = 0; ///< compared pixels where one spectrum is all zero
};

/// Everything compareCubes finds.
struct ComparisonReport {
  ScaleFit fit = ScaleFit::None;
  long pixels = 0;                ///< compared pixels
  long excludedPixels = 0;        ///< pixels of the regions left out (ComparisonInputs::excluded)
  std::vector<BandFigures> bands; ///< one per band
  SamFigures sam;
  std::vector<float> samMapDeg; ///< [pixel] angle in degrees; NaN where not compared
  std::vector<RegionFigures> regions;
};

/// How region spectra become colours.
struct ColourOptions {
  /// Reflectances: XYZ under `illuminant`, white = the illuminant (Y = 1). Otherwise radiances:
  /// XYZ of the spectrum itself, white = the illuminant's chromaticity at the largest Y of the
  /// regions' means (both sides), so the brightest region has L* = 100.
  bool reflectance = false;
  Spectrum illuminant; ///< the white (D65 by default in nxcompare)
};

/// Adds CIELAB colours and CIEDE2000 to each region of `report` from its mean spectra at the
/// bands' wavelengths (linear between bands, the end values held beyond them).
void addRegionColours(ComparisonReport& report, const std::vector<double>& wavelengthNm,
                      const ColourOptions& options);

/// Compares the cubes. The render is scaled as `fit` says (the factors are reported), then
/// per band: bias, RMSE, relative RMSE, PSNR, z-scores; per pixel: the spectral angle
/// acos(r.c / (|r| |c|)) between scaled render and capture; per region: mean spectra and mean
/// angle. Throws nx::Error when no pixel is compared or a compared value is not finite.
ComparisonReport compareCubes(const ComparisonInputs& in, ScaleFit fit);

} // namespace nx

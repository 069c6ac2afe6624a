#pragma once
// The film: per-pixel sums of band radiance and XYZ over a rectangle of the image (the whole
// image or a crop), filled tile by tile without locks.

#include <algorithm>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "integrators/path_contributions.h"
#include "integrators/relight_pattern.h"
#include "io/aov_names.h"
#include "spectra/cie.h"
#include "spectra/sampled_wavelengths.h"
#include "spectra/sensor.h"
#include "spectra/wavelength_sampler.h"

namespace nx {

/// A pixel rectangle [x0, x1) x [y0, y1) of the full image.
struct PixelRect {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  int width() const { return x1 - x0; }
  int height() const { return y1 - y0; }
};

/// Estimates of band-averaged radiance and of XYZ for each pixel of a rectangle, as sums over
/// samples. Coordinates are those of the full image.
class Film {
public:
  /// A film for `rect` of a width x height image, with the given output bands.
  /// With `whiteReference`, it also accumulates the white-reference AOV (addWhiteSample).
  Film(int width, int height, const PixelRect& rect, const Sensor& bands,
       bool whiteReference = false);
  /// A film covering the whole image.
  Film(int width, int height, const Sensor& bands)
      : Film(width, height, {0, 0, width, height}, bands) {}
  /// True when the film holds the white reference.
  bool hasWhite() const { return !whiteSums_.empty(); }
  /// Keeps component layers (EXR layers "<name>.S0.<band>nm", e.g. "reflected", "light.lamp"),
  /// each estimated per band like the radiance, with its variance; zeroes them.
  void setLayers(std::vector<std::string> names);
  /// Keeps the ground-truth layers `kinds` (their channels in that order, as AovEvaluator
  /// fills them), averaged over the samples like the radiance; zeroes them.
  void setAovs(std::vector<AovKind> kinds);
  /// The ground-truth layers kept (none unless setAovs was called).
  const std::vector<AovKind>& aovKinds() const { return aovKinds_; }
  /// Their channels.
  int aovChannels() const { return aovChannels_; }
  /// Component layers kept (0 unless setLayers was called).
  int layerCount() const { return static_cast<int>(layerNames_.size()); }
  /// The name of layer l.
  const std::string& layerName(int l) const { return layerNames_[static_cast<size_t>(l)]; }
  /// Keeps the transport of a relightable render on `pattern` for the light sources `sources`
  /// (RelightSpectra; per pixel sources x pattern size sums per replicate, in single
  /// precision); zeroes it. `spectra`: each source's spectrum as rendered, averaged over the
  /// grid's bins.
  void setRelight(std::shared_ptr<const RelightPattern> pattern, std::vector<std::string> sources,
                  std::vector<std::vector<double>> spectra);
  /// The pattern kept (null unless setRelight was called).
  const RelightPattern* relightPattern() const { return relightPattern_.get(); }
  /// Light sources of the transport kept.
  int relightSources() const { return static_cast<int>(relightSourceNames_.size()); }
  /// Their names.
  const std::vector<std::string>& relightSourceNames() const { return relightSourceNames_; }
  /// Their spectra as rendered, per bin of the grid.
  const std::vector<std::vector<double>>& relightSourceSpectra() const {
    return relightSourceSpectra_;
  }
  /// Sets the sources' excitation guides per bin (a render told its relighting targets;
  /// RelightLayers::guides), kept for the image.
  void setRelightGuides(std::vector<std::vector<std::vector<double>>> guides) {
    relightGuides_ = std::move(guides);
  }
  /// The sources' excitation guides per bin; empty without targets.
  const std::vector<std::vector<std::vector<double>>>& relightGuides() const {
    return relightGuides_;
  }

  int width() const { return width_; }   ///< full image width
  int height() const { return height_; } ///< full image height
  const PixelRect& rect() const { return rect_; }
  const Sensor& bands() const { return bands_; }
  /// Shortest wavelength the renderer traces: the bands' range joined with the CIE range
  /// (360-830 nm), so that XYZ, RGB, the preview and Variance.Y integrate the colour matching
  /// functions over their whole range whatever the bands.
  double tracedMinNm() const { return tracedMinNm(bands_); }
  /// Longest wavelength the renderer traces (see tracedMinNm()).
  double tracedMaxNm() const { return tracedMaxNm(bands_); }
  /// The shortest wavelength traced for a sensor.
  static double tracedMinNm(const Sensor& s) {
    return std::min(s.minNm(), static_cast<double>(kCieMinNm));
  }
  /// The longest wavelength traced for a sensor.
  static double tracedMaxNm(const Sensor& s) {
    return std::max(s.maxNm(), static_cast<double>(kCieMaxNm));
  }

  /// Accumulator for one pixel's samples (lives on the stack of the tile task), kept per
  /// replicate: [0] the even-numbered samples, [1] the odd-numbered ones.
  struct Pixel {
    std::vector<double> bands[2];   ///< sums of band estimates
    double xyz[2][3] = {};          ///< sums of XYZ estimates
    std::vector<double> white;      ///< sums of white-reference band estimates (if kept)
    std::vector<double> layers[2];  ///< sums of component layers' band estimates, [layer][band]
    std::vector<double> relight[2]; ///< sums of the transport, [group][entry]
    std::vector<double> aov;        ///< sums of the ground-truth channels (if kept)
    uint32_t samples[2] = {0, 0};
  };

  /// A zeroed pixel accumulator for this film.
  Pixel newPixel() const;
  /// Zeroes an accumulator for the next pixel (no allocation).
  static void resetPixel(Pixel& p) {
    for (int r = 0; r < 2; ++r) {
      std::fill(p.bands[r].begin(), p.bands[r].end(), 0.0);
      p.xyz[r][0] = p.xyz[r][1] = p.xyz[r][2] = 0;
      p.samples[r] = 0;
      std::fill(p.layers[r].begin(), p.layers[r].end(), 0.0);
      std::fill(p.relight[r].begin(), p.relight[r].end(), 0.0);
    }
    std::fill(p.white.begin(), p.white.end(), 0.0);
    std::fill(p.aov.begin(), p.aov.end(), 0.0);
  }
  /// Samples an accumulator holds.
  static uint32_t samplesIn(const Pixel& p) { return p.samples[0] + p.samples[1]; }

  /// Adds one sample: radiance L carried by the lanes of `lambda` (sensor wavelengths, drawn
  /// over the traced range), each lane weighted 1 / (kLanes pdf). Band b receives
  /// L R_b / integral(R_b) (a box: L / width inside it); XYZ receives L * cmf / integral(y-bar) for
  /// lanes inside 360-830 nm. Samples with a non-finite value are dropped and counted (returns
  /// false). `odd`: the sample belongs to the second of the two independently scrambled replicates
  /// (odd sample numbers); the difference of the two half means estimates the error.
  bool addSample(Pixel& pixel, const SampledWavelengths& lambda, const SampledSpectrum& L,
                 bool odd) const;

  /// Adds the component layers of a sample that addSample accepted (layerCount() spectra, with
  /// the sample's lanes and replicate), weighted like its radiance.
  void addLayerSamples(Pixel& pixel, const SampledWavelengths& lambda,
                       const SampledSpectrum* layers, bool odd) const;

  /// The weight of each lane of a sample in sum_b adjoint[b] * (the pixel's band b), per unit
  /// radiance of the lane: sum_b adjoint[b] R_b(lambda) / integral(R_b) / (kLanes pdf) (as
  /// addSample weighs it; the mean's 1 / N not included).
  SampledSpectrum adjointWeights(const SampledWavelengths& lambda, const float* adjoint) const;

  /// Adds the transport of a sample that addSample accepted (a relightable render), each
  /// contribution weighted like the radiance into the bands responding at its lane's
  /// wavelength. Returns the contributions that fell outside the pattern (none, unless the
  /// pattern misses a path the scene has: they are dropped and counted).
  uint64_t addRelightSamples(Pixel& pixel, const SampledWavelengths& lambda,
                             const std::vector<RelightContribution>& contributions, bool odd) const;

  /// Adds one sample of the white reference (radiance L of a white Lambertian surface at the
  /// first hit) to the bands, like addSample; false (and nothing added) when not finite.
  bool addWhiteSample(Pixel& pixel, const SampledWavelengths& lambda,
                      const SampledSpectrum& L) const;

  /// Adds one sample's ground-truth channels (aovChannels() values).
  static void addAovSample(Pixel& pixel, const float* values) {
    for (size_t c = 0; c < pixel.aov.size(); ++c) pixel.aov[c] += values[c];
  }

  /// Adds a pixel's accumulated samples (each pixel is written by one tile task at a time).
  void add(int x, int y, const Pixel& pixel);
  /// Sets a pixel from stored means, variances of the means (null: unknown) and their sample
  /// count (resuming from a file).
  void setFromMeans(int x, int y, const float* bandMeans, const float* bandVariances,
                    const double xyzMean[3], double yVariance, uint32_t samples,
                    uint32_t oddSamples, const float* whiteMeans = nullptr);

  /// Sets the ground-truth channels of a pixel already set by setFromMeans from stored means.
  void setAovFromMeans(int x, int y, const float* means);
  /// Mean of ground-truth channel c in pixel (x, y) (0 before a sample).
  double aovMean(int x, int y, int c) const {
    const size_t i = index(x, y);
    return counts_[i] ? aovSums_[i * static_cast<size_t>(aovChannels_) + static_cast<size_t>(c)] /
                            counts_[i]
                      : 0.0;
  }

  /// Sets layer l of a pixel already set by setFromMeans from stored means and variances of the
  /// means (null: unknown).
  void setLayerFromMeans(int x, int y, int l, const float* means, const float* variances);

  /// The part of this film over `r` (inside its rectangle), with the same sums.
  Film cropped(const PixelRect& r) const;

  /// Mean band radiance of pixel (x, y), band b.
  double bandMean(int x, int y, int b) const;
  /// Mean white-reference radiance of pixel (x, y), band b (0 without the white reference).
  double whiteMean(int x, int y, int b) const;
  /// Mean radiance of component layer l in pixel (x, y), band b.
  double layerMean(int x, int y, int l, int b) const;
  /// Estimated variance of that mean (from the two replicates, like bandVariance).
  double layerVariance(int x, int y, int l, int b) const;
  /// Mean transport of pixel (x, y), light group g, pattern entry e.
  double relightMean(int x, int y, int g, int e) const;
  /// Its signed half-difference (A - B) / 2 of the two replicates' means (0 before both).
  double relightHalfDifference(int x, int y, int g, int e) const;
  /// Mean XYZ of pixel (x, y).
  Xyz xyzMean(int x, int y) const;
  /// Samples taken in pixel (x, y).
  uint32_t samples(int x, int y) const { return counts_[index(x, y)]; }
  /// Estimated variance of the pixel's mean band radiance: (A - B)^2 / 4 for the means A and B
  /// of the two independent replicates (even and odd sample numbers); 0 before one of each.
  double bandVariance(int x, int y, int b) const;
  /// Estimated variance of the pixel's mean luminance Y.
  double yVariance(int x, int y) const;
  /// Estimated relative RMS error of the image: sqrt(mean of the pixels' Y variances) over
  /// the mean Y (infinite before two samples per pixel or on a black image).
  double relativeRmsError() const;
  /// The same for band b: sqrt(mean of the pixels' band variances) over the band's mean
  /// (infinite before two samples per pixel; NaN for a band that is black everywhere).
  double bandRelativeRmsError(int b) const;
  /// The largest bandRelativeRmsError over the bands whose centroid lies in [loNm, hiNm]
  /// (black bands skipped); infinite when no band qualifies or before two samples per pixel.
  double worstBandRelativeRmsError(double loNm, double hiNm) const;

private:
  size_t index(int x, int y) const {
    return static_cast<size_t>(y - rect_.y0) * rect_.width() + (x - rect_.x0);
  }
  int width_, height_;
  PixelRect rect_;
  Sensor bands_;
  int nBands_;
  SensorResponseTable responses_; ///< R / integral(R) of every band, per wavelength
  /// x-bar, y-bar, z-bar / integral(y-bar) at 1 nm from kCieMinNm, interleaved (one lookup
  /// touches one place), with a zero entry past the end.
  std::vector<float> cmf_;
  std::vector<double> bandSums_;    ///< [pixel][band]
  std::vector<double> bandOddSums_; ///< [pixel][band]
  std::vector<double> xyzSums_;     ///< [pixel][3]
  std::vector<double> yOddSums_;    ///< [pixel]
  std::vector<uint32_t> oddCounts_; ///< [pixel]
  std::vector<uint32_t> counts_;
  std::vector<double> whiteSums_; ///< [pixel][band]; empty without the white reference
  std::vector<AovKind> aovKinds_;
  int aovChannels_ = 0;
  std::vector<double> aovSums_; ///< [pixel][channel]
  std::vector<std::string> layerNames_;
  std::vector<double> layerSums_;    ///< [pixel][layer][band]
  std::vector<double> layerOddSums_; ///< [pixel][layer][band]
  std::shared_ptr<const RelightPattern> relightPattern_;
  std::vector<std::string> relightSourceNames_;
  std::vector<std::vector<double>> relightSourceSpectra_;
  std::vector<std::vector<std::vector<double>>> relightGuides_;
  std::vector<float> relightSums_;    ///< [pixel][group][entry]
  std::vector<float> relightOddSums_; ///< [pixel][group][entry]
};

} // namespace nx

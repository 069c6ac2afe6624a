#pragma once
// Spectral distributions as a closed set of kinds, dispatched statically (no virtual calls).

#include <algorithm>
#include <cstdint>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

namespace nx {

/// Shortest wavelength that can be traced (nm): bands lie in [kTraceMinNm, kTraceMaxNm], every
/// spectrum of a scene is validated over it, analytic spectra are tabulated over it.
inline constexpr double kTraceMinNm = 300;
/// Longest wavelength that can be traced (nm).
inline constexpr double kTraceMaxNm = 1100;

/// Largest emitted radiance (W m^-2 sr^-1 nm^-1) or point-light intensity (W sr^-1 nm^-1) a
/// scene may hold: the Sun's spectral radiance is about 2.6e4, so this leaves seven orders of
/// magnitude while every sample value, and its square in the error estimate, stays finite in
/// single precision (an emission of 1e21 made every Variance channel infinite; 1e39 every sample).
inline constexpr double kMaxEmission = 1e12;

/// The same value at every wavelength.
struct ConstantSpectrum {
  double value = 0;
  double operator()(double) const { return value; }
};

/// A Gaussian with the given peak value (not area-normalised).
struct GaussianSpectrum {
  double meanNm = 550, sigmaNm = 34, peak = 1;
  double operator()(double nm) const;
};

/// The skew-Cauchy density of Zheng, Sato & Sato (ECCV 2014):
/// f = g / (pi (g^2 + d^2)) * (atan(w d / g) / pi + 1/2), d = lambda - location. As written
/// (fluorescence spec) it integrates to 1/2 for every skew w; users normalise it.
struct SkewCauchySpectrum {
  double locationNm = 550, widthNm = 20, skew = 0;
  double operator()(double nm) const;
};

/// Planck's law: spectral radiance of a black body in W m^-2 sr^-1 nm^-1.
struct BlackbodySpectrum {
  double kelvin = 6504;
  double operator()(double nm) const;
};

/// Piecewise-linear interpolation of (wavelength, value) pairs; outside their range zero, or
/// the first/last value when holdEnds is set (a scene's extrapolate="hold").
struct TabulatedSpectrum {
  std::vector<double> nm;    ///< strictly increasing wavelengths
  std::vector<double> value; ///< one value per wavelength
  bool holdEnds = false;     ///< beyond the table: the end values instead of zero
  /// 1 / the step of a (nearly) uniform grid, found by buildIndex(); 0: not indexed so.
  double invStep = 0;
  /// Unevenly spaced tables indexed by buildIndex(): 1 / the width of a cell of [nm.front(),
  /// nm.back()], and per cell the interval its start lies in; empty: binary search.
  double invCell = 0;
  std::vector<uint32_t> cellFirst{};
  double operator()(double nm) const;
  /// Lets operator() find the interval by arithmetic, with the same interval and value as
  /// the binary search: directly when the wavelengths are evenly spaced (each within half a
  /// step of the grid), else through cells at least as wide as the closest two wavelengths
  /// (at most kIndexCells of them), from whose first interval a step or two settles it.
  void buildIndex();
  /// Most cells of an unevenly spaced table's index.
  static constexpr size_t kIndexCells = 4096;
};

/// The sigmoid polynomial's wavelength variable is x = (nm - kSigmoidStartNm) / kSigmoidSpanNm.
inline constexpr double kSigmoidStartNm = 360.0, kSigmoidSpanNm = 470.0;

/// The smooth sigmoid-polynomial spectrum of Jakob & Hanika (EGSR 2019):
/// s(lambda) = 1/2 + p / (2 sqrt(1 + p^2)), p = c0 x^2 + c1 x + c2, x = (lambda-360)/470.
struct SigmoidPolynomialSpectrum {
  double c0 = 0, c1 = 0, c2 = 0;
  double operator()(double nm) const;
};

/// Samples of a smooth spectrum on a uniform grid, linearly interpolated; zero outside it.
/// Used at render time for the analytic kinds (an exp or atan per evaluation becomes a lookup).
struct DenseSpectrum {
  static constexpr double startNm = kTraceMinNm, stepNm = 0.25; ///< grid (1/stepNm exact)
  std::vector<float> value;
  double operator()(double nm) const { return at(static_cast<float>(nm)); }
  /// Value at nm in single precision: the render loop's lookup (a multiply, no division).
  float at(float nm) const {
    const float x = (nm - static_cast<float>(startNm)) * static_cast<float>(1.0 / stepNm);
    if (!(x >= 0) || x > static_cast<float>(value.size() - 1)) return 0.0f;
    const size_t i = std::min(static_cast<size_t>(x), value.size() - 2);
    const float t = x - static_cast<float>(i);
    return value[i] + (value[i + 1] - value[i]) * t;
  }
};

/// Any spectrum nxrender knows, times a scale factor.
class Spectrum {
public:
  using Kind =
      std::variant<ConstantSpectrum, GaussianSpectrum, SkewCauchySpectrum, BlackbodySpectrum,
                   TabulatedSpectrum, SigmoidPolynomialSpectrum, DenseSpectrum>;

  /// Zero everywhere.
  Spectrum() : kind_(ConstantSpectrum{0}) {}
  /// A spectrum of the given kind, scaled by `scale`.
  template <typename K>
  Spectrum(K kind, double scale = 1) : kind_(std::move(kind)), scale_(scale) {}

  /// Value at wavelength nm.
  double operator()(double nm) const {
    return scale_ * std::visit([nm](const auto& k) { return k(nm); }, kind_);
  }
  /// Values at several wavelengths with one dispatch.
  template <typename Lambdas, typename Out>
  void evaluate(const Lambdas& nm, Out& out) const {
    std::visit(
        [&](const auto& k) {
          using K = std::decay_t<decltype(k)>;
          if constexpr (std::is_same_v<K, DenseSpectrum>) {
            const float scale = static_cast<float>(scale_);
            for (size_t i = 0; i < nm.size(); ++i) out[i] = scale * k.at(static_cast<float>(nm[i]));
          } else if constexpr (std::is_same_v<K, ConstantSpectrum>) {
            const float v = static_cast<float>(scale_ * k.value);
            for (size_t i = 0; i < nm.size(); ++i) out[i] = v;
          } else {
            for (size_t i = 0; i < nm.size(); ++i) out[i] = static_cast<float>(scale_ * k(nm[i]));
          }
        },
        kind_);
  }

  /// The same spectrum multiplied by s.
  Spectrum scaled(double s) const {
    Spectrum r = *this;
    r.scale_ *= s;
    return r;
  }
  /// The scale factor applied to the kind's values.
  double scale() const { return scale_; }
  /// The underlying kind.
  const Kind& kind() const { return kind_; }
  /// True when the value does not depend on wavelength.
  bool isConstant() const { return std::holds_alternative<ConstantSpectrum>(kind_); }

private:
  Kind kind_;
  double scale_ = 1;
};

/// The spectrum as the renderer evaluates it: analytic kinds (Gaussian, skew-Cauchy, black
/// body, sigmoid polynomial) sampled every 0.25 nm over the traced range (relative interpolation
/// error below 1e-4 for the smooth built-in spectra); constant and tabulated kinds unchanged.
Spectrum forRendering(const Spectrum& s);

/// A tabulated spectrum from (wavelength, value) pairs; `where` names the source for errors
/// (wavelengths must be finite and strictly increasing, at least two pairs).
TabulatedSpectrum makeTabulated(std::vector<double> nm, std::vector<double> value,
                                const std::string& where);

/// A tabulated spectrum read from a CSV file: wavelength in nm, then the value; an optional
/// header line is allowed. With `column`, the file may hold several value columns and the
/// header names the one to take. Errors name the file and line.
TabulatedSpectrum readSpectrumCsv(const std::string& path, const std::string& column = "");

/// The same from the file's text; `source` names it in errors.
TabulatedSpectrum parseSpectrumCsv(const std::string& text, const std::string& source,
                                   const std::string& column = "");

} // namespace nx

#pragma once
// A spectral sensor: the list of channel responses a render is recorded through (uniform
// boxes, boxes with their own edges, Gaussians from centres and FWHMs, or measured responses).

#include <optional>
#include <string>
#include <vector>

#include "spectra/bands.h"
#include "spectra/spectrum.h"

namespace nx {

/// The shape of one channel's relative spectral response R(l).
enum class ResponseShape {
  Box,      ///< 1 on [lo, hi), 0 elsewhere
  Gaussian, ///< exp(-(l - c)^2 / (2 sigma^2)) within c +- 2 FWHM, 0 beyond (mass lost < 3e-6)
  Table,    ///< piecewise linear through measured (nm, response) pairs, 0 outside them
};

/// One channel of a sensor.
struct SensorChannel {
  std::string name;                         ///< the CSV header's name, or generated
  ResponseShape shape = ResponseShape::Box; ///< kind of response
  double lo = 0, hi = 0;                    ///< support: R = 0 outside [lo, hi]
  double centreNm = 0, fwhmNm = 0;          ///< Gaussian parameters (box: centre and width)
  std::vector<double> nm, response;         ///< Table knots
  /// R at nm (relative; peak 1 for boxes and Gaussians).
  double operator()(double nm) const;
  /// A measured channel's nominal centre: its name when that is a wavelength in nm ("650",
  /// "650nm", "650 nm", as vendors' SRF headers give the band list); none otherwise.
  std::optional<double> nominalNm() const;
};

/// A sensor: an ordered list of channels. A channel's value for radiance L is
/// integral(R L dl) / integral(R dl); it is named at its centroid integral(l R) / integral(R).
class Sensor {
public:
  /// Uniform boxes START:END:STEP (the default sensor is SpectralBands::defaults()).
  Sensor(const SpectralBands& bands = SpectralBands::defaults());

  /// Parses a sensor description: "START:END:STEP" (uniform boxes), "boxes:LO-HI,LO-HI,..."
  /// (boxes with their own edges), "gaussian:CENTRES@FWHM" (CENTRES a comma list or
  /// START:END:STEP, FWHM one value or one per centre), or "table:" followed by CSV text (as
  /// toString writes a measured sensor). Errors name `where` and say what was expected.
  static Sensor parse(const std::string& text, const std::string& where = "sensor");
  /// A measured sensor from CSV text: header `nm,<band name>,...`, then rows of the wavelength
  /// and one relative response per band. `source` names the file in file:line errors.
  static Sensor fromCsv(const std::string& text, const std::string& source);
  /// The same from a file.
  static Sensor readCsv(const std::string& path);
  /// This measured sensor with its bands named by the nominal centres in `centres` ("a,b,c" or
  /// START:END:STEP, one per band): the band list a vendor's SRF header does not give.
  /// Throws nx::Error (prefixed by `where`) for a count that differs or a sensor not measured.
  Sensor withNominalCentres(const std::string& centres, const std::string& where) const;
  /// Gaussian channels; `fwhm` holds one value for all or one per centre.
  static Sensor gaussian(const std::vector<double>& centres, const std::vector<double>& fwhm,
                         const std::string& where);

  /// Number of channels.
  int count() const { return static_cast<int>(channels_.size()); }
  /// Channel i.
  const SensorChannel& channel(int i) const { return channels_[static_cast<size_t>(i)]; }
  /// Centroid of channel i (nm): integral(l R) / integral(R).
  double centroid(int i) const { return centroid_[static_cast<size_t>(i)]; }
  /// The wavelength naming channel i's EXR layer: a measured channel's nominal centre (its
  /// name, the sensor's own band list) when it has one, else its centroid.
  double channelNm(int i) const { return channelNm_[static_cast<size_t>(i)]; }
  /// Full width at half maximum of channel i (nm; a box's width).
  double fwhm(int i) const { return fwhm_[static_cast<size_t>(i)]; }
  /// integral(R dl) of channel i (nm), as the film integrates it.
  double responseIntegral(int i) const { return integral_[static_cast<size_t>(i)]; }
  /// Shortest wavelength any channel responds to.
  double minNm() const { return minNm_; }
  /// Longest wavelength any channel responds to.
  double maxNm() const { return maxNm_; }
  /// The uniform boxes this sensor is, when it is one (uniformBoxes() tells).
  const SpectralBands& uniformBands() const { return bands_; }
  /// True for a START:END:STEP sensor.
  bool uniformBoxes() const { return uniform_; }
  /// The description parse() reads back as exactly this sensor (stored in the EXR).
  std::string toString() const;
  /// A one-line summary for logs ("31 boxes 395-705 nm").
  std::string summary() const;

  /// integral(R s) / integral(R) for channel i (fine quadrature of the response the film uses).
  double average(const Spectrum& s, int i) const;

  /// Grid on which the film tabulates the responses: cell width (nm) and origin (minNm()).
  /// Box edges of uniform sensors fall on cell boundaries; smooth responses are resolved to
  /// 1/40 of their FWHM (at most 0.05 nm).
  double cellNm() const { return cellNm_; }
  /// Number of cells over [minNm(), maxNm()].
  int cellCount() const { return cellCount_; }

  /// A sensor of these channels (validated: non-negative, non-empty, within 300-1100 nm,
  /// distinct centroids); `where` names the source in errors.
  static Sensor fromChannels(std::vector<SensorChannel> channels, const std::string& where);

private:
  void finish(const std::string& where);
  std::vector<SensorChannel> channels_;
  std::vector<double> centroid_, fwhm_, integral_, channelNm_;
  double minNm_ = 0, maxNm_ = 0, cellNm_ = 0.05;
  int cellCount_ = 0;
  SpectralBands bands_;
  bool uniform_ = false;
};

/// integral(R_i s) / integral(R_i): what band i of `sensor` records for radiance s.
inline double bandAverage(const Spectrum& s, const Sensor& sensor, int i) {
  return sensor.average(s, i);
}

/// R_i(l) / integral(R_i) of every channel, tabulated for the render loop: per cell of the
/// sensor's grid, the channels that respond there and their normalised response, linear
/// across the cell (a + b f for the position f in [0, 1) within the cell). One lookup per
/// wavelength, no search, no allocation.
class SensorResponseTable {
public:
  /// One channel's normalised response across one cell.
  struct Entry {
    int channel;
    float a, b;
  };
  /// The table of `sensor`.
  explicit SensorResponseTable(const Sensor& sensor);
  /// Calls add(channel, weight) for every channel responding at nm (weight R / integral(R)).
  template <typename Add>
  void forEach(float nm, Add&& add) const {
    const float x = (nm - origin_) * invCell_;
    if (!(x >= 0 && x < cells_)) return;
    const int k = static_cast<int>(x);
    const float f = x - static_cast<float>(k);
    for (uint32_t e = first_[static_cast<size_t>(k)]; e < first_[static_cast<size_t>(k) + 1]; ++e) {
      const Entry& en = entries_[e];
      add(en.channel, en.a + en.b * f);
    }
  }

private:
  float origin_, invCell_, cells_;
  std::vector<uint32_t> first_; ///< entries of cell k: [first_[k], first_[k + 1])
  std::vector<Entry> entries_;
};

} // namespace nx

#include "spectra/sensor.h"

#include <algorithm>
#include <cctype>
#include <cfloat>
#include <cmath>
#include <cstdlib>
#include <set>
#include <sstream>

#include "core/error.h"
#include "core/file_text.h"
#include "core/number_text.h"
#include "core/text_table.h"

namespace nx {
namespace {

constexpr double kFwhmPerSigma = 2.3548200450309493; // 2 sqrt(2 ln 2)
constexpr double kGaussianReachFwhm = 2.0;           // support: centre +- 2 FWHM
constexpr double kMaxCellNm = 0.05;
constexpr int kMaxCells = 1 << 22;
constexpr int kMaxChannels = 4096;

std::string rangeText() {
  return numberText(kTraceMinNm) + "-" + numberText(kTraceMaxNm) + " nm";
}

std::vector<std::string> splitOn(const std::string& s, char sep) {
  std::vector<std::string> out;
  std::string cell;
  std::istringstream in(s);
  while (std::getline(in, cell, sep)) out.push_back(cell);
  if (!s.empty() && s.back() == sep) out.emplace_back();
  return out;
}

// "a,b,c" or "START:END:STEP" (the centres of uniform bands).
std::vector<double> parseCentres(const std::string& text, const std::string& where) {
  if (text.find(':') != std::string::npos) {
    const SpectralBands b = SpectralBands::parse(text);
    std::vector<double> c;
    for (int i = 0; i < b.count(); ++i) c.push_back(b.centre(i));
    return c;
  }
  std::vector<double> out;
  for (const std::string& cell : splitOn(text, ','))
    out.push_back(parseNumber(cell, where, "a wavelength in nm"));
  return out;
}

} // namespace

std::optional<double> SensorChannel::nominalNm() const {
  if (shape != ResponseShape::Table) return std::nullopt;
  std::string t = name;
  t.erase(0, t.find_first_not_of(" \t"));
  while (!t.empty() && std::isspace(static_cast<unsigned char>(t.back()))) t.pop_back();
  if (t.size() > 2 && (t.ends_with("nm") || t.ends_with("NM"))) t.resize(t.size() - 2);
  while (!t.empty() && std::isspace(static_cast<unsigned char>(t.back()))) t.pop_back();
  if (t.empty() || !(std::isdigit(static_cast<unsigned char>(t[0])))) return std::nullopt;
  const char* end = nullptr;
  const double v = strtodC(t.c_str(), &end);
  if (end != t.c_str() + t.size() || !(v >= 100 && v <= 2000)) return std::nullopt;
  return v;
}

double SensorChannel::operator()(double l) const {
  if (!(l >= lo && l <= hi)) return 0.0;
  switch (shape) {
  case ResponseShape::Box:
    return l < hi ? 1.0 : 0.0;
  case ResponseShape::Gaussian: {
    const double s = fwhmNm / kFwhmPerSigma, d = (l - centreNm) / s;
    return std::exp(-0.5 * d * d);
  }
  case ResponseShape::Table: {
    const auto it = std::upper_bound(nm.begin(), nm.end(), l);
    if (it == nm.begin()) return 0.0;
    if (it == nm.end()) return l == nm.back() ? response.back() : 0.0;
    const size_t j = static_cast<size_t>(it - nm.begin());
    const double t = (l - nm[j - 1]) / (nm[j] - nm[j - 1]);
    return response[j - 1] + t * (response[j] - response[j - 1]);
  }
  }
  return 0.0;
}

Sensor::Sensor(const SpectralBands& bands) : bands_(bands), uniform_(true) {
  for (int i = 0; i < bands.count(); ++i) {
    SensorChannel c;
    c.shape = ResponseShape::Box;
    c.lo = bands.lower(i);
    c.hi = bands.upper(i);
    c.centreNm = bands.centre(i);
    c.fwhmNm = bands.stepNm;
    c.name = numberText(c.centreNm) + " nm";
    channels_.push_back(std::move(c));
  }
  finish("bands '" + bands.toString() + "'");
}

Sensor Sensor::fromChannels(std::vector<SensorChannel> channels, const std::string& where) {
  Sensor s;
  s.channels_ = std::move(channels);
  s.uniform_ = false;
  s.finish(where);
  return s;
}

Sensor Sensor::withNominalCentres(const std::string& centres, const std::string& where) const {
  const std::vector<double> nm = parseCentres(centres, where);
  if (nm.size() != channels_.size())
    throw Error(where + ": expected " + std::to_string(channels_.size()) +
                " nominal centres (one per band of the sensor), found " +
                std::to_string(nm.size()));
  std::vector<SensorChannel> channels = channels_;
  for (size_t i = 0; i < nm.size(); ++i) {
    if (channels[i].shape != ResponseShape::Table)
      throw Error(where + ": expected nominal centres for measured responses (a CSV), found " +
                  "band '" + channels[i].name + "' of another kind (it is named at its centre)");
    if (!(nm[i] >= 100 && nm[i] <= 2000))
      throw Error(where + ": expected nominal centres in nm within [100, 2000], found " +
                  numberText(nm[i]));
    channels[i].name = exactNumberText(nm[i]);
  }
  return fromChannels(std::move(channels), where);
}

Sensor Sensor::gaussian(const std::vector<double>& centres, const std::vector<double>& fwhm,
                        const std::string& where) {
  if (centres.empty()) throw Error(where + ": expected at least one band centre, found none");
  if (fwhm.size() != 1 && fwhm.size() != centres.size())
    throw Error(where + ": expected one FWHM or one per centre (" + std::to_string(centres.size()) +
                "), found " + std::to_string(fwhm.size()));
  std::vector<SensorChannel> channels;
  for (size_t i = 0; i < centres.size(); ++i) {
    SensorChannel c;
    c.shape = ResponseShape::Gaussian;
    c.centreNm = centres[i];
    c.fwhmNm = fwhm.size() == 1 ? fwhm[0] : fwhm[i];
    if (!(c.fwhmNm >= 0.1))
      throw Error(where + ": expected a FWHM of at least 0.1 nm, found " + numberText(c.fwhmNm) +
                  " nm for the band at " + numberText(c.centreNm) + " nm");
    c.lo = c.centreNm - kGaussianReachFwhm * c.fwhmNm;
    c.hi = c.centreNm + kGaussianReachFwhm * c.fwhmNm;
    c.name = numberText(c.centreNm) + " nm";
    channels.push_back(std::move(c));
  }
  return fromChannels(std::move(channels), where);
}

Sensor Sensor::fromCsv(const std::string& text, const std::string& source) {
  const NumberTable t = parseNumberTable(text, source, /*allowHeader=*/true);
  if (t.header.size() < 2)
    throw Error(
        source + ":1: expected a header 'nm,<band name>,...' naming at least one band, " +
        (t.header.empty() ? std::string("found no header") : "found '" + t.header[0] + "' alone"));
  const size_t nBands = t.header.size() - 1;
  std::vector<SensorChannel> channels(nBands);
  std::set<std::string> names;
  for (size_t b = 0; b < nBands; ++b) {
    channels[b].shape = ResponseShape::Table;
    channels[b].name = t.header[b + 1];
    if (channels[b].name.empty() || !names.insert(channels[b].name).second)
      throw Error(source + ":1: expected distinct, non-empty band names, found '" +
                  channels[b].name + "' " + (channels[b].name.empty() ? "" : "twice"));
  }
  double previous = -INFINITY;
  for (const TableRow& row : t.rows) {
    const std::string at = source + ":" + std::to_string(row.line);
    if (row.values.size() != t.header.size())
      throw Error(at + ": expected " + std::to_string(t.header.size()) +
                  " values (wavelength and one response per band), found " +
                  std::to_string(row.values.size()));
    const double l = row.values[0];
    if (!(l > previous))
      throw Error(at + ": expected wavelengths in increasing order, found " + numberText(l) +
                  " nm after " + numberText(previous) + " nm");
    previous = l;
    for (size_t b = 0; b < nBands; ++b) {
      const double r = row.values[b + 1];
      if (!(r >= 0))
        throw Error(at + ": expected a non-negative response for band '" + channels[b].name +
                    "', found " + numberText(r));
      channels[b].nm.push_back(l);
      channels[b].response.push_back(r);
    }
  }
  for (SensorChannel& c : channels) {
    // The support: from the last zero before the first non-zero response to the first zero
    // after the last one (rows of zeros beyond it may lie outside the traced range).
    size_t first = c.nm.size(), last = 0;
    for (size_t j = 0; j < c.nm.size(); ++j)
      if (c.response[j] > 0) {
        first = std::min(first, j);
        last = j;
      }
    if (first == c.nm.size())
      throw Error(source + ": expected a response above zero somewhere for band '" + c.name +
                  "', found only zeros");
    const size_t from = first > 0 ? first - 1 : 0, to = std::min(last + 1, c.nm.size() - 1);
    c.nm = std::vector<double>(c.nm.begin() + static_cast<long>(from),
                               c.nm.begin() + static_cast<long>(to) + 1);
    c.response = std::vector<double>(c.response.begin() + static_cast<long>(from),
                                     c.response.begin() + static_cast<long>(to) + 1);
    c.lo = c.nm.front();
    c.hi = c.nm.back();
    if (c.lo == c.hi)
      throw Error(source + ": expected band '" + c.name +
                  "' to respond over an interval, found a single wavelength (" + numberText(c.lo) +
                  " nm); give the zeros on either side");
  }
  Sensor s = fromChannels(std::move(channels), source);
  return s;
}

Sensor Sensor::readCsv(const std::string& path) {
  return fromCsv(readRegularFile(path, 64u << 20, "sensor file"), path);
}

Sensor Sensor::parse(const std::string& text, const std::string& where) {
  const auto startsWith = [&](const char* p) { return text.rfind(p, 0) == 0; };
  if (startsWith("table:")) return fromCsv(text.substr(6), where);
  if (startsWith("gaussian:")) {
    const std::string body = text.substr(9);
    const auto at = body.find('@');
    if (at == std::string::npos)
      throw Error(where + ": expected gaussian:CENTRES@FWHM, found '" + text + "'");
    std::vector<double> fwhm;
    for (const std::string& cell : splitOn(body.substr(at + 1), ','))
      fwhm.push_back(parseNumber(cell, where, "a FWHM in nm"));
    return gaussian(parseCentres(body.substr(0, at), where), fwhm, where);
  }
  if (startsWith("boxes:")) {
    std::vector<SensorChannel> channels;
    for (const std::string& cell : splitOn(text.substr(6), ',')) {
      const auto dash = cell.find('-', 1);
      if (dash == std::string::npos)
        throw Error(where + ": expected boxes as LO-HI in nm, found '" + cell + "'");
      SensorChannel c;
      c.shape = ResponseShape::Box;
      c.lo = parseNumber(cell.substr(0, dash), where, "a lower band edge in nm");
      c.hi = parseNumber(cell.substr(dash + 1), where, "an upper band edge in nm");
      if (!(c.hi - c.lo >= 1e-3))
        throw Error(where + ": expected a box at least 0.001 nm wide (LO < HI), found '" + cell +
                    "'");
      c.centreNm = 0.5 * (c.lo + c.hi);
      c.fwhmNm = c.hi - c.lo;
      c.name = numberText(c.centreNm) + " nm";
      channels.push_back(std::move(c));
    }
    return fromChannels(std::move(channels), where);
  }
  return Sensor(SpectralBands::parse(text));
}

void Sensor::finish(const std::string& where) {
  const size_t n = channels_.size();
  if (n == 0) throw Error(where + ": expected at least one band, found none");
  if (n > kMaxChannels)
    throw Error(where + ": expected at most " + std::to_string(kMaxChannels) + " bands, found " +
                std::to_string(n));
  // Measured responses are relative: each is divided by its peak, so any finite scale (counts,
  // 1e-300 or 1e300) gives the same channel, and no integral below can overflow or underflow.
  for (SensorChannel& c : channels_) {
    if (c.shape != ResponseShape::Table) continue;
    double peak = 0;
    for (double r : c.response) {
      if (!(r >= 0 && r <= DBL_MAX))
        throw Error(where + ": expected finite, non-negative responses for band '" + c.name +
                    "', found " + numberText(r));
      peak = std::max(peak, r);
    }
    if (!(peak >= DBL_MIN))
      throw Error(where + ": expected band '" + c.name + "' to peak at a normal number (at least " +
                  numberText(DBL_MIN) + "; responses are relative, any scale above that is " +
                  "normalised), found a peak of " + numberText(peak));
    for (double& r : c.response) r /= peak;
  }
  minNm_ = INFINITY;
  maxNm_ = -INFINITY;
  double cell = kMaxCellNm;
  for (const SensorChannel& c : channels_) {
    if (!(c.lo >= kTraceMinNm && c.hi <= kTraceMaxNm))
      throw Error(where + ": expected every band within " + rangeText() + ", found band '" +
                  c.name + "' responding over " + numberText(c.lo) + "-" + numberText(c.hi) +
                  " nm");
    minNm_ = std::min(minNm_, c.lo);
    maxNm_ = std::max(maxNm_, c.hi);
    if (c.shape == ResponseShape::Gaussian) cell = std::min(cell, c.fwhmNm / 40);
    if (c.shape == ResponseShape::Box && !uniform_) cell = std::min(cell, (c.hi - c.lo) / 20);
    for (size_t j = 1; j < c.nm.size(); ++j) cell = std::min(cell, c.nm[j] - c.nm[j - 1]);
  }
  // Uniform boxes: a whole number of cells per band, so that band edges are cell edges.
  if (uniform_) cell = bands_.stepNm / std::ceil(bands_.stepNm / kMaxCellNm);
  const double cells = std::ceil((maxNm_ - minNm_) / cell - 1e-9);
  if (!(cells <= kMaxCells))
    throw Error(where + ": expected responses the renderer can tabulate (at most " +
                std::to_string(kMaxCells) + " cells), found " + numberText(cells) + " cells of " +
                numberText(cell) + " nm over " + numberText(minNm_) + "-" + numberText(maxNm_) +
                " nm (a very narrow band over a wide range)");
  cellNm_ = cell;
  cellCount_ = std::max(1, static_cast<int>(cells));

  // Integral, centroid and FWHM of the response as the film tabulates it (linear per cell).
  centroid_.assign(n, 0);
  fwhm_.assign(n, 0);
  integral_.assign(n, 0);
  channelNm_.assign(n, 0);
  std::set<std::string> layerNames;
  for (size_t i = 0; i < n; ++i) {
    const SensorChannel& c = channels_[i];
    if (c.shape == ResponseShape::Box) {
      integral_[i] = c.hi - c.lo;
      centroid_[i] = c.centreNm;
      fwhm_[i] = c.hi - c.lo;
    } else {
      const int k0 = static_cast<int>(std::floor((c.lo - minNm_) / cellNm_));
      const int k1 = static_cast<int>(std::ceil((c.hi - minNm_) / cellNm_));
      double area = 0, moment = 0, peak = 0;
      for (int k = k0; k < k1; ++k) {
        const double x0 = minNm_ + k * cellNm_, x1 = x0 + cellNm_;
        const double r0 = c(x0), r1 = c(x1);
        area += 0.5 * (r0 + r1) * cellNm_;
        // integral over the cell of l (r0 + (r1 - r0) t), l = x0 + h t
        moment += cellNm_ * (x0 * 0.5 * (r0 + r1) + cellNm_ * (r0 / 6 + r1 / 3));
        peak = std::max(peak, std::max(r0, r1));
      }
      if (!(area > 0))
        throw Error(where + ": expected band '" + c.name +
                    "' to have a response with positive area, found none");
      integral_[i] = area;
      centroid_[i] = c.shape == ResponseShape::Gaussian ? c.centreNm : moment / area;
      if (c.shape == ResponseShape::Gaussian) {
        fwhm_[i] = c.fwhmNm;
      } else { // width between the outermost crossings of half the peak
        double lo = c.lo, hi = c.hi;
        for (size_t j = 1; j < c.nm.size(); ++j)
          if (c.response[j] >= 0.5 * peak && c.response[j - 1] < 0.5 * peak) {
            lo = c.nm[j - 1] + (0.5 * peak - c.response[j - 1]) /
                                   (c.response[j] - c.response[j - 1]) * (c.nm[j] - c.nm[j - 1]);
            break;
          }
        for (size_t j = c.nm.size() - 1; j > 0; --j)
          if (c.response[j - 1] >= 0.5 * peak && c.response[j] < 0.5 * peak) {
            hi = c.nm[j - 1] + (c.response[j - 1] - 0.5 * peak) /
                                   (c.response[j - 1] - c.response[j]) * (c.nm[j] - c.nm[j - 1]);
            break;
          }
        fwhm_[i] = hi - lo;
      }
    }
    if (!(std::isfinite(centroid_[i]) && std::isfinite(fwhm_[i]) && std::isfinite(integral_[i])))
      throw Error(where + ": expected band '" + c.name +
                  "' to have a finite centroid, width and area, found " + numberText(centroid_[i]) +
                  " nm, " + numberText(fwhm_[i]) + " nm, " + numberText(integral_[i]) + " nm");
    const std::optional<double> nominal = c.nominalNm();
    channelNm_[i] = nominal ? *nominal : centroid_[i];
    const std::string name = fixedText(channelNm_[i], 6);
    if (!layerNames.insert(name).second)
      throw Error(where +
                  (nominal ? ": expected bands with distinct nominal centres (their names, "
                             "which name the image's channels), found two at "
                           : ": expected bands with distinct centroids (they name the image's "
                             "channels), found two at ") +
                  std::string(name) + " nm");
  }
}

double Sensor::average(const Spectrum& s, int i) const {
  const SensorChannel& c = channel(i);
  // Gauss-Legendre, 3 points per cell: exact for the tabulated response times a polynomial
  // of degree 4 within a cell.
  static const double gx[3] = {0.5 - 0.5 * std::sqrt(0.6), 0.5, 0.5 + 0.5 * std::sqrt(0.6)};
  static const double gw[3] = {5.0 / 18, 8.0 / 18, 5.0 / 18};
  double sum = 0;
  if (c.shape == ResponseShape::Box) {
    const int n = std::max(1, static_cast<int>(std::ceil((c.hi - c.lo) / 0.1)));
    const double h = (c.hi - c.lo) / n;
    for (int k = 0; k < n; ++k)
      for (int q = 0; q < 3; ++q) sum += gw[q] * h * s(c.lo + (k + gx[q]) * h);
    return sum / integral_[static_cast<size_t>(i)];
  }
  const int k0 = static_cast<int>(std::floor((c.lo - minNm_) / cellNm_));
  const int k1 = static_cast<int>(std::ceil((c.hi - minNm_) / cellNm_));
  for (int k = k0; k < k1; ++k) {
    const double x0 = minNm_ + k * cellNm_;
    const double r0 = c(x0), r1 = c(x0 + cellNm_);
    if (r0 == 0 && r1 == 0) continue;
    for (int q = 0; q < 3; ++q)
      sum += gw[q] * cellNm_ * (r0 + (r1 - r0) * gx[q]) * s(x0 + gx[q] * cellNm_);
  }
  return sum / integral_[static_cast<size_t>(i)];
}

std::string Sensor::toString() const {
  if (uniform_) return bands_.toString();
  std::string out;
  const ResponseShape shape = channels_[0].shape;
  bool oneShape = true;
  for (const SensorChannel& c : channels_) oneShape = oneShape && c.shape == shape;
  if (oneShape && shape == ResponseShape::Box) {
    out = "boxes:";
    for (size_t i = 0; i < channels_.size(); ++i)
      out += (i ? "," : "") + exactNumberText(channels_[i].lo) + "-" +
             exactNumberText(channels_[i].hi);
    return out;
  }
  if (oneShape && shape == ResponseShape::Gaussian) {
    out = "gaussian:";
    for (size_t i = 0; i < channels_.size(); ++i)
      out += (i ? "," : "") + exactNumberText(channels_[i].centreNm);
    out += "@";
    for (size_t i = 0; i < channels_.size(); ++i)
      out += (i ? "," : "") + exactNumberText(channels_[i].fwhmNm);
    return out;
  }
  // Measured (or mixed) responses: a CSV table on the union of the knots.
  std::set<double> knots;
  for (const SensorChannel& c : channels_) {
    if (c.shape != ResponseShape::Table)
      throw Error("a sensor mixing measured and analytic bands has no text form");
    knots.insert(c.nm.begin(), c.nm.end());
  }
  out = "table:nm";
  for (const SensorChannel& c : channels_) out += "," + c.name;
  out += "\n";
  for (double l : knots) {
    out += exactNumberText(l);
    for (const SensorChannel& c : channels_) out += "," + exactNumberText(c(l));
    out += "\n";
  }
  return out;
}

std::string Sensor::summary() const {
  const char* kind = "bands";
  if (channels_[0].shape == ResponseShape::Gaussian) kind = "Gaussian bands";
  if (channels_[0].shape == ResponseShape::Table) kind = "measured bands";
  if (channels_[0].shape == ResponseShape::Box) kind = "box bands";
  return std::to_string(count()) + " " + kind + " responding over " + numberText(minNm_) + "-" +
         numberText(maxNm_) + " nm";
}

SensorResponseTable::SensorResponseTable(const Sensor& sensor)
    : origin_(static_cast<float>(sensor.minNm())),
      invCell_(static_cast<float>(1.0 / sensor.cellNm())),
      cells_(static_cast<float>(sensor.cellCount())) {
  const int nCells = sensor.cellCount();
  const double h = sensor.cellNm(), origin = sensor.minNm();
  std::vector<std::vector<Entry>> perCell(static_cast<size_t>(nCells));
  for (int i = 0; i < sensor.count(); ++i) {
    const SensorChannel& c = sensor.channel(i);
    const double norm = 1.0 / sensor.responseIntegral(i);
    const int k0 = std::max(0, static_cast<int>(std::floor((c.lo - origin) / h)));
    const int k1 = std::min(nCells, static_cast<int>(std::ceil((c.hi - origin) / h)));
    for (int k = k0; k < k1; ++k) {
      const double x0 = origin + k * h, x1 = x0 + h;
      double a, b;
      if (c.shape == ResponseShape::Box) { // the fraction of the cell the box covers
        const double cover = std::min(c.hi, x1) - std::max(c.lo, x0);
        if (!(cover > 1e-9 * h)) continue;
        a = std::min(1.0, cover / h);
        b = 0;
      } else {
        a = c(x0);
        b = c(x1) - a;
        if (a == 0 && b == 0) continue;
      }
      perCell[static_cast<size_t>(k)].push_back(
          {i, static_cast<float>(a * norm), static_cast<float>(b * norm)});
    }
  }
  first_.reserve(static_cast<size_t>(nCells) + 1);
  first_.push_back(0);
  for (const auto& cell : perCell) {
    entries_.insert(entries_.end(), cell.begin(), cell.end());
    first_.push_back(static_cast<uint32_t>(entries_.size()));
  }
}

} // namespace nx

#include "spectra/camera_simulation.h"

#include <algorithm>
#include <cmath>
#include <random>

#include "core/error.h"
#include "core/hash.h"

namespace nx {
namespace {

constexpr double kPlanck = 6.62607015e-34;  // J s (exact, SI 2019)
constexpr double kLightSpeed = 299792458.0; // m / s (exact)
constexpr double kPi = 3.14159265358979323846;

// SplitMix64 (Steele, Lea & Flood, OOPSLA 2014): a small generator for the standard
// distributions, seeded per (pixel, band).
struct SplitMix64 {
  using result_type = uint64_t;
  uint64_t state;
  static constexpr uint64_t min() { return 0; }
  static constexpr uint64_t max() { return ~uint64_t{0}; }
  uint64_t operator()() {
    uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }
};

double qeOf(const CameraModel& c, double band) {
  return c.quantumEfficiency.size() == 1 ? c.quantumEfficiency[0]
                                         : c.quantumEfficiency[static_cast<size_t>(band)];
}

} // namespace

double meanSignalElectrons(const CameraModel& c, const CameraBand& b, double bandIndex,
                           double radiance) {
  const double irradiance =
      c.irradianceScale > 0 ? c.irradianceScale * radiance
                            : kPi * c.lensTransmittance * radiance / (4 * c.fNumber * c.fNumber);
  const double area = c.pixelPitchUm * 1e-6 * c.pixelPitchUm * 1e-6;
  const double energy = irradiance * b.widthNm * area * c.exposureSeconds; // J
  const double photonEnergy = kPlanck * kLightSpeed / (b.centroidNm * 1e-9);
  return qeOf(c, bandIndex) * energy / photonEnergy;
}

void validateCameraModel(const CameraModel& c, int bands, const std::string& where) {
  auto require = [&](bool ok, const std::string& what, double found) {
    if (!ok) throw Error(where + ": expected " + what + ", found " + numberText(found));
  };
  require(c.fNumber > 0 && std::isfinite(c.fNumber), "a positive f-number", c.fNumber);
  require(c.lensTransmittance > 0 && c.lensTransmittance <= 1, "a lens transmittance in (0, 1]",
          c.lensTransmittance);
  require(c.irradianceScale >= 0 && std::isfinite(c.irradianceScale),
          "a non-negative irradiance scale", c.irradianceScale);
  require(c.exposureSeconds > 0 && std::isfinite(c.exposureSeconds), "a positive exposure time",
          c.exposureSeconds);
  require(c.pixelPitchUm > 0 && std::isfinite(c.pixelPitchUm), "a positive pixel pitch",
          c.pixelPitchUm);
  require(c.fullWellElectrons > 0 && std::isfinite(c.fullWellElectrons), "a positive full well",
          c.fullWellElectrons);
  require(c.readNoiseElectrons >= 0 && std::isfinite(c.readNoiseElectrons),
          "a non-negative read noise", c.readNoiseElectrons);
  require(c.darkCurrentElectrons >= 0 && std::isfinite(c.darkCurrentElectrons),
          "a non-negative dark current", c.darkCurrentElectrons);
  require(c.gainDnPerElectron > 0 && std::isfinite(c.gainDnPerElectron), "a positive gain",
          c.gainDnPerElectron);
  require(c.offsetDn >= 0 && std::isfinite(c.offsetDn), "a non-negative offset", c.offsetDn);
  require(c.bitDepth >= 1 && c.bitDepth <= 32, "a bit depth of 1 to 32", c.bitDepth);
  if (c.quantumEfficiency.size() != 1 && static_cast<int>(c.quantumEfficiency.size()) != bands)
    throw Error(where + ": expected one quantum efficiency or one per band (" +
                std::to_string(bands) + "), found " + std::to_string(c.quantumEfficiency.size()));
  for (double q : c.quantumEfficiency)
    require(q >= 0 && q <= 1, "quantum efficiencies in [0, 1]", q);
}

std::vector<float> cameraVariance(const CameraModel& c, const std::vector<CameraBand>& bands,
                                  const std::vector<float>& radiance,
                                  const std::vector<float>& radianceVariance, size_t pixels) {
  const size_t nb = bands.size();
  std::vector<float> v(pixels * nb);
  const double dark = c.darkCurrentElectrons * c.exposureSeconds, k = c.gainDnPerElectron;
  for (size_t b = 0; b < nb; ++b) {
    const double perRadiance = meanSignalElectrons(c, bands[b], static_cast<double>(b), 1.0);
    for (size_t p = 0; p < pixels; ++p) {
      const size_t i = p * nb + b;
      const double signal = std::min(perRadiance * radiance[i] + dark, c.fullWellElectrons);
      double var = k * k * (signal + c.readNoiseElectrons * c.readNoiseElectrons) + 1.0 / 12;
      if (!radianceVariance.empty()) var += k * k * perRadiance * perRadiance * radianceVariance[i];
      v[i] = static_cast<float>(var);
    }
  }
  return v;
}

std::vector<float> simulateCamera(const CameraModel& c, const std::vector<CameraBand>& bands,
                                  const std::vector<float>& radiance, size_t pixels) {
  const size_t nb = bands.size();
  std::vector<float> dn(pixels * nb);
  const double maxDn = std::ldexp(1.0, c.bitDepth) - 1;
  const double dark = c.darkCurrentElectrons * c.exposureSeconds;
  for (size_t p = 0; p < pixels; ++p)
    for (size_t b = 0; b < nb; ++b) {
      const double l = radiance[p * nb + b];
      if (!std::isfinite(l) || l < 0)
        throw Error("expected finite non-negative radiances, found " + numberText(l) +
                    " at pixel " + std::to_string(p) + " in band " +
                    numberText(bands[b].centroidNm) + " nm");
      SplitMix64 rng{(uint64_t{hash4(static_cast<uint32_t>(p), static_cast<uint32_t>(p >> 32),
                                     static_cast<uint32_t>(b), c.seed)}
                      << 32) |
                     hash4(static_cast<uint32_t>(b), static_cast<uint32_t>(p), c.seed, 0x5eedU)};
      const double mean = meanSignalElectrons(c, bands[b], static_cast<double>(b), l) + dark;
      double electrons = 0;
      if (mean > 0) {
        if (mean < 1e15) {
          std::poisson_distribution<long long> poisson(mean);
          electrons = static_cast<double>(poisson(rng));
        } else {
          electrons = mean; // beyond any full well
        }
      }
      electrons = std::min(electrons, c.fullWellElectrons);
      if (c.readNoiseElectrons > 0)
        electrons += std::normal_distribution<double>(0.0, c.readNoiseElectrons)(rng);
      const double value = std::nearbyint(c.gainDnPerElectron * electrons + c.offsetDn);
      dn[p * nb + b] = static_cast<float>(std::clamp(value, 0.0, maxDn));
    }
  return dn;
}

} // namespace nx

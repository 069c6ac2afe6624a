#pragma once
// What a camera records of a spectral radiance image: irradiance at the sensor, photo-
// electrons with shot noise, dark current, full well, read noise, gain, offset, quantisation
// (the EMVA 1288 linear camera model).

#include <cstdint>
#include <string>
#include <vector>

namespace nx {

/// A camera's optics and sensor.
struct CameraModel {
  double fNumber = 4;           ///< N: irradiance = pi T L / (4 N^2) (on axis, distant scene)
  double lensTransmittance = 1; ///< T
  double irradianceScale =
      0; ///< if > 0: irradiance = this x L instead (W m^-2 nm^-1 per radiance unit)
  double exposureSeconds = 0.01;
  double pixelPitchUm = 5.5; ///< square pixels: area = pitch^2
  std::vector<double> quantumEfficiency = {
      0.6}; ///< electrons per photon: one value, or one per band
  double fullWellElectrons = 20000;
  double readNoiseElectrons = 5;    ///< standard deviation
  double darkCurrentElectrons = 10; ///< electrons per second (mean)
  double gainDnPerElectron = 0.1;   ///< K
  double offsetDn = 64;             ///< black level
  int bitDepth = 12;
  uint32_t seed = 0;
};

/// One band of the input: its centroid and the integral of its response (nm), so that
/// band value x width is the band's share of the spectral irradiance.
struct CameraBand {
  double centroidNm = 0, widthNm = 0;
};

/// Mean photo-electrons per pixel for band radiance L (before noise and the full well):
/// E = irradiance(L) (W m^-2 nm^-1), photons = E x width x area x t / (h c / lambda), times QE.
double meanSignalElectrons(const CameraModel& camera, const CameraBand& band, double bandIndex,
                           double radiance);

/// Throws nx::Error (naming `where`) unless every parameter is physical: positive f-number,
/// exposure, pitch, full well, gain; QE in [0, 1] with one value or one per band; bit depth
/// 1-32; non-negative noise, dark current and offset.
void validateCameraModel(const CameraModel& camera, int bands, const std::string& where);

/// Digital numbers for radiances[pixel][band]: electrons ~ Poisson(signal + dark x t), capped
/// at the full well, plus Normal(0, read noise); DN = round(K e + offset) clamped to
/// [0, 2^bits - 1]. The random numbers of (pixel, band) depend only on them and the seed.
std::vector<float> simulateCamera(const CameraModel& camera, const std::vector<CameraBand>& bands,
                                  const std::vector<float>& radiance, size_t pixels);

/// The variance (DN^2) of each simulated value: the camera's own noise at its mean,
/// K^2 (min(signal, full well) + dark + read^2) + 1/12 (quantisation), plus the input's
/// variance carried through, (K g)^2 var L with g the electrons per unit radiance (the render's
/// Monte Carlo error; `radianceVariance` empty: none). What a comparison of a synthetic capture
/// needs to give z-scores of N(0, 1) (docs/compare.md).
std::vector<float> cameraVariance(const CameraModel& camera, const std::vector<CameraBand>& bands,
                                  const std::vector<float>& radiance,
                                  const std::vector<float>& radianceVariance, size_t pixels);

} // namespace nx

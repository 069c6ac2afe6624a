// The simulated camera against theory: the radiometric chain's mean electrons in closed form,
// the mean and variance of DN against Poisson + Gaussian + quantisation, the Poisson regime,
// the full well and bit depth, determinism, and parameter checks.

#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "spectra/camera_simulation.h"

namespace nx {
namespace {

TEST(CameraSimulation, MeanElectronsFollowTheRadiometricChain) {
  CameraModel c;
  c.fNumber = 2;
  c.lensTransmittance = 0.9;
  c.exposureSeconds = 1e-3;
  c.pixelPitchUm = 10;
  c.quantumEfficiency = {0.5};
  const CameraBand band{500, 10};
  // E = pi T L / (4 N^2); energy = E x 10 nm x (10 um)^2 x 1 ms; photon = h c / 500 nm.
  const double e = M_PI * 0.9 * 1.0 / 16, energy = e * 10 * 1e-10 * 1e-3;
  const double photons = energy / (6.62607015e-34 * 299792458.0 / 500e-9);
  EXPECT_NEAR(meanSignalElectrons(c, band, 0, 1.0), 0.5 * photons, 1e-9 * photons);
  c.irradianceScale = 0.25; // irradiance = 0.25 L instead of the lens formula
  EXPECT_NEAR(meanSignalElectrons(c, band, 0, 2.0),
              0.5 * 0.5 * 10 * 1e-10 * 1e-3 / (6.62607015e-34 * 299792458.0 / 500e-9), 1e-3);
}

// A camera whose band turns radiance 1 into exactly `electrons` mean photo-electrons.
CameraModel cameraFor(double electrons, CameraBand& band) {
  CameraModel c;
  c.irradianceScale = 1;
  c.exposureSeconds = 1;
  c.pixelPitchUm = 1;
  band = {500, 1};
  const double perUnit = meanSignalElectrons(c, band, 0, 1.0) / c.quantumEfficiency[0];
  c.quantumEfficiency = {electrons / perUnit};
  if (c.quantumEfficiency[0] > 1)
    c.exposureSeconds = c.quantumEfficiency[0], c.quantumEfficiency = {1};
  return c;
}

TEST(CameraSimulation, DnMeanAndVarianceMatchPoissonPlusGaussian) {
  CameraBand band;
  CameraModel c = cameraFor(1000, band);
  c.darkCurrentElectrons = 50 / c.exposureSeconds; // 50 e- over the exposure
  c.readNoiseElectrons = 10;
  c.gainDnPerElectron = 0.5;
  c.offsetDn = 100;
  c.fullWellElectrons = 1e6;
  c.bitDepth = 16;
  const size_t n = 40000;
  const std::vector<float> dn = simulateCamera(c, {band}, std::vector<float>(n, 1.0f), n);
  double sum = 0, sum2 = 0;
  for (float v : dn) sum += v, sum2 += double(v) * v;
  const double mean = sum / n, var = (sum2 - n * mean * mean) / (n - 1);
  const double mu = 1050, theoryMean = 0.5 * mu + 100;
  const double theoryVar = 0.25 * (mu + 100) + 1.0 / 12; // K^2 (mu + read^2) + rounding
  EXPECT_NEAR(mean, theoryMean, 5 * std::sqrt(theoryVar / n));
  EXPECT_NEAR(var, theoryVar, 5 * theoryVar * std::sqrt(2.0 / (n - 1)));
}

// cameraVariance states the simulation's variance: against the empirical variance of many
// simulated values, and with an input radiance variance carried through as (K g)^2 var L
// (checked by simulating inputs that themselves vary with that variance).
TEST(CameraSimulation, StatedVarianceIsTheSimulatedOne) {
  CameraBand band;
  CameraModel c = cameraFor(1000, band);
  c.darkCurrentElectrons = 50 / c.exposureSeconds;
  c.readNoiseElectrons = 10;
  c.gainDnPerElectron = 0.5;
  c.fullWellElectrons = 1e6;
  c.bitDepth = 16;
  const size_t n = 40000;
  const std::vector<float> ones(n, 1.0f);
  const std::vector<float> stated = cameraVariance(c, {band}, ones, {}, n);
  const std::vector<float> dn = simulateCamera(c, {band}, ones, n);
  double sum = 0, sum2 = 0;
  for (float v : dn) sum += v, sum2 += double(v) * v;
  const double var = (sum2 - sum * sum / n) / (n - 1);
  EXPECT_NEAR(var, stated[0], 5 * stated[0] * std::sqrt(2.0 / (n - 1)));
  // Inputs 1 +- 0.1 (two values, variance 0.01): the stated variance adds (K g)^2 0.01.
  std::vector<float> varying(n), inputVar(n, 0.01f);
  for (size_t i = 0; i < n; ++i) varying[i] = i % 2 ? 1.1f : 0.9f;
  const std::vector<float> dn2 = simulateCamera(c, {band}, varying, n);
  sum = sum2 = 0;
  for (float v : dn2) sum += v, sum2 += double(v) * v;
  const double var2 = (sum2 - sum * sum / n) / (n - 1);
  const double want = cameraVariance(c, {band}, ones, inputVar, n)[0];
  EXPECT_NEAR(var2, want, 5 * want * std::sqrt(2.0 / (n - 1)));
  EXPECT_GT(want, 1.5 * stated[0]); // the input's share is not negligible: the check can fail
}

TEST(CameraSimulation, LowSignalIsPoisson) {
  CameraBand band;
  CameraModel c = cameraFor(2, band);
  c.darkCurrentElectrons = 0;
  c.readNoiseElectrons = 0;
  c.gainDnPerElectron = 1;
  c.offsetDn = 0;
  const size_t n = 50000;
  const std::vector<float> dn = simulateCamera(c, {band}, std::vector<float>(n, 1.0f), n);
  int counts[4] = {0, 0, 0, 0};
  for (float v : dn)
    if (v < 4) ++counts[static_cast<int>(v)];
  for (int k = 0; k < 4; ++k) {
    const double p = std::exp(-2.0) * std::pow(2.0, k) / std::tgamma(k + 1.0);
    EXPECT_NEAR(counts[k] / double(n), p, 5 * std::sqrt(p * (1 - p) / n)) << k;
  }
}

TEST(CameraSimulation, FullWellAndBitDepthClip) {
  CameraBand band;
  CameraModel c = cameraFor(1e7, band);
  c.readNoiseElectrons = 0;
  c.fullWellElectrons = 30000;
  c.gainDnPerElectron = 0.1;
  c.offsetDn = 10;
  c.bitDepth = 16;
  EXPECT_EQ(simulateCamera(c, {band}, {1.0f}, 1)[0], 3010.0f);
  c.bitDepth = 10;
  EXPECT_EQ(simulateCamera(c, {band}, {1.0f}, 1)[0], 1023.0f);
  c.darkCurrentElectrons = 0; // no light, no dark current, no read noise: the offset alone
  EXPECT_EQ(simulateCamera(c, {band}, {0.0f}, 1)[0], 10.0f);
}

TEST(CameraSimulation, DeterministicPerPixelAndSeed) {
  CameraBand band;
  CameraModel c = cameraFor(500, band);
  std::vector<float> image(100);
  for (size_t i = 0; i < image.size(); ++i) image[i] = 0.01f * static_cast<float>(i);
  const std::vector<float> a = simulateCamera(c, {band}, image, 100);
  const std::vector<float> part =
      simulateCamera(c, {band}, std::vector<float>(image.begin(), image.begin() + 10), 10);
  for (size_t i = 0; i < 10; ++i) EXPECT_EQ(a[i], part[i]);
  EXPECT_EQ(a, simulateCamera(c, {band}, image, 100));
  c.seed = 1;
  EXPECT_NE(a, simulateCamera(c, {band}, image, 100));
}

TEST(CameraSimulation, UnphysicalParametersAreRefused) {
  CameraModel c;
  c.fNumber = 0;
  EXPECT_THROW(validateCameraModel(c, 3, "cam"), Error);
  c = CameraModel{};
  c.quantumEfficiency = {0.5, 0.6};
  EXPECT_THROW(validateCameraModel(c, 3, "cam"), Error);
  c.quantumEfficiency = {1.5};
  EXPECT_THROW(validateCameraModel(c, 3, "cam"), Error);
  c = CameraModel{};
  c.bitDepth = 40;
  EXPECT_THROW(validateCameraModel(c, 3, "cam"), Error);
  EXPECT_NO_THROW(validateCameraModel(CameraModel{}, 3, "cam"));
  EXPECT_THROW(simulateCamera(CameraModel{}, {{500, 10}}, {NAN}, 1), Error);
}

} // namespace
} // namespace nx

// The comparison figures against values computed here independently: scaled captures, constant
// offsets, known angles, noise z-scores, regions.

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/error.h"
#include "spectra/band_resampling.h"
#include "spectra/cube_comparison.h"

namespace nx {
namespace {

struct Cubes {
  int w = 6, h = 4, nb = 5;
  std::vector<float> render, capture, variance;
  ComparisonInputs inputs() const {
    ComparisonInputs in;
    in.width = w, in.height = h, in.bands = nb;
    for (int b = 0; b < nb; ++b) in.wavelengthNm.push_back(400 + 50 * b);
    in.render = render.data();
    in.capture = capture.data();
    in.renderVariance = variance.empty() ? nullptr : variance.data();
    return in;
  }
};

// A render with a different spectrum at every pixel.
Cubes cubes() {
  Cubes c;
  for (int p = 0; p < c.w * c.h; ++p)
    for (int b = 0; b < c.nb; ++b)
      c.render.push_back(0.2f + 0.05f * static_cast<float>((p * 7 + b * 3) % 11));
  return c;
}

TEST(CubeComparison, ScaledCaptureHasZeroAngleAndItsScaleIsFound) {
  Cubes c = cubes();
  for (float v : c.render) c.capture.push_back(1.07f * v);
  const ComparisonReport global = compareCubes(c.inputs(), ScaleFit::Global);
  for (const BandFigures& f : global.bands) {
    EXPECT_NEAR(f.scale, 1.07, 1e-6);
    EXPECT_NEAR(f.rmse, 0, 1e-6);
    EXPECT_NEAR(f.bias, 0, 1e-6);
  }
  EXPECT_NEAR(global.sam.meanDeg, 0, 1e-3);
  EXPECT_NEAR(global.sam.maxDeg, 0, 1e-3);
  // Unscaled: the angle is still 0 (SAM ignores scale); the bias is -0.07 x the band mean.
  const ComparisonReport none = compareCubes(c.inputs(), ScaleFit::None);
  EXPECT_NEAR(none.sam.maxDeg, 0, 1e-3);
  for (const BandFigures& f : none.bands) {
    EXPECT_EQ(f.scale, 1);
    EXPECT_NEAR(f.bias, -0.07 * f.renderMean, 1e-6);
    EXPECT_NEAR(f.relativeRmse, f.rmse / f.renderMean, 1e-12);
  }
}

TEST(CubeComparison, ConstantOffsetGivesItsRmseBiasAndPsnr) {
  Cubes c = cubes();
  for (float v : c.render) c.capture.push_back(v - 0.03f);
  const ComparisonReport r = compareCubes(c.inputs(), ScaleFit::None);
  for (size_t b = 0; b < r.bands.size(); ++b) {
    const BandFigures& f = r.bands[b];
    EXPECT_NEAR(f.bias, 0.03, 1e-6);
    EXPECT_NEAR(f.rmse, 0.03, 1e-6);
    double maxCapture = 0, meanRender = 0;
    for (int p = 0; p < c.w * c.h; ++p) {
      maxCapture = std::max(maxCapture, double(c.capture[static_cast<size_t>(p * c.nb) + b]));
      meanRender += c.render[static_cast<size_t>(p * c.nb) + b] / double(c.w * c.h);
    }
    EXPECT_NEAR(f.psnrDb, 20 * std::log10(maxCapture / 0.03), 1e-3);
    EXPECT_NEAR(f.renderMean, meanRender, 1e-6);
    EXPECT_NEAR(f.relativeRmse, 0.03 / meanRender, 1e-5);
  }
}

// Two-band spectra at a known angle: render (1, 0), capture (cos t, sin t).
TEST(CubeComparison, SpectralAngleStatisticsOfKnownAngles) {
  Cubes c;
  c.w = 5, c.h = 1, c.nb = 2;
  const double deg[5] = {1, 2, 3, 4, 10};
  for (double d : deg) {
    c.render.insert(c.render.end(), {1.0f, 0.0f});
    c.capture.push_back(static_cast<float>(std::cos(d * M_PI / 180)));
    c.capture.push_back(static_cast<float>(std::sin(d * M_PI / 180)));
  }
  const ComparisonReport r = compareCubes(c.inputs(), ScaleFit::None);
  EXPECT_NEAR(r.sam.meanDeg, 4.0, 1e-4);
  EXPECT_NEAR(r.sam.medianDeg, 3.0, 1e-4);
  EXPECT_NEAR(r.sam.maxDeg, 10.0, 1e-4);
  EXPECT_NEAR(r.sam.p95Deg, 4 + 0.8 * 6, 1e-4); // rank 3.8 between 4 and 10
  for (int p = 0; p < 5; ++p) EXPECT_NEAR(r.samMapDeg[static_cast<size_t>(p)], deg[p], 1e-4);
}

// Differences that are the render's own noise give |z| of order 1 and rms z near 1; a real
// bias of 5 standard errors is flagged.
TEST(CubeComparison, NoiseZScoresFollowTheVariance) {
  Cubes c;
  c.w = 100, c.h = 100, c.nb = 2;
  std::mt19937 rng(3);
  std::normal_distribution<double> noise(0, 1);
  const double sigma = 0.01;
  for (int p = 0; p < c.w * c.h; ++p)
    for (int b = 0; b < 2; ++b) {
      c.capture.push_back(0.5f);
      c.variance.push_back(static_cast<float>(sigma * sigma));
      const double bias = b == 1 ? 5 * sigma / 100 : 0; // 5 standard errors of the mean
      c.render.push_back(static_cast<float>(0.5 + bias + sigma * noise(rng)));
    }
  const ComparisonReport r = compareCubes(c.inputs(), ScaleFit::None);
  EXPECT_LT(std::abs(r.bands[0].zMean), 4.0);
  EXPECT_NEAR(r.bands[0].rmsZ, 1.0, 0.05);
  EXPECT_GT(r.bands[1].zMean, 2.0); // 5 +- 1
  EXPECT_LT(r.bands[1].zMean, 8.0);
  // Without variances there are no z-scores.
  c.variance.clear();
  EXPECT_TRUE(std::isnan(compareCubes(c.inputs(), ScaleFit::None).bands[0].zMean));
}

TEST(CubeComparison, PerBandScalesAndRegions) {
  Cubes c = cubes();
  for (size_t i = 0; i < c.render.size(); ++i)
    c.capture.push_back(c.render[i] * (1.0f + 0.1f * static_cast<float>(i % 5)));
  ComparisonInputs in = c.inputs();
  std::vector<uint8_t> left(24, 0), right(24, 0);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 6; ++x) (x < 3 ? left : right)[static_cast<size_t>(y * 6 + x)] = 1;
  in.regions = {{"left", left}, {"right", right}};
  const ComparisonReport r = compareCubes(in, ScaleFit::PerBand);
  for (int b = 0; b < 5; ++b)
    EXPECT_NEAR(r.bands[static_cast<size_t>(b)].scale, 1.0 + 0.1 * b, 1e-6);
  ASSERT_EQ(r.regions.size(), 2u);
  EXPECT_EQ(r.regions[0].pixels, 12);
  double mean = 0;
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 3; ++x) mean += c.capture[static_cast<size_t>((y * 6 + x) * 5 + 2)] / 12.0;
  EXPECT_NEAR(r.regions[0].captureMean[2], mean, 1e-6);
  EXPECT_NEAR(r.regions[0].renderMean[2], mean, 1e-6); // scaled render = capture
  // Only the left half compared.
  in.regions = {{"left", left}};
  EXPECT_EQ(compareCubes(in, ScaleFit::None).pixels, 12);
}

TEST(CubeComparison, NonFiniteValuesAndEmptyRegionsAreErrors) {
  Cubes c = cubes();
  c.capture = c.render;
  c.capture[7 * 5 + 2] = NAN; // pixel 1,1 band 500 nm
  EXPECT_THROW(compareCubes(c.inputs(), ScaleFit::None), Error);
  try {
    compareCubes(c.inputs(), ScaleFit::None);
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("capture value nan at pixel 1,1 in band 500 nm"),
              std::string::npos)
        << e.what();
  }
  ComparisonInputs in = c.inputs();
  // Left out, the pixel no longer matters; it is counted.
  in.excluded.assign(24, 0);
  in.excluded[7] = 1;
  const ComparisonReport r = compareCubes(in, ScaleFit::None);
  EXPECT_EQ(r.pixels, 23);
  EXPECT_EQ(r.excludedPixels, 1);
  EXPECT_NEAR(r.bands[2].rmse, 0, 1e-12);
  in.excluded.clear();
  in.regions = {{"none", std::vector<uint8_t>(24, 0)}};
  EXPECT_THROW(compareCubes(in, ScaleFit::None), Error);
}

// Resampling a spectrum linear in wavelength through Gaussian bands gives its value at each
// band's centre (a symmetric response averages a linear function to its centre value).
TEST(BandResampling, LinearSpectrumThroughGaussiansGivesCentreValues) {
  std::vector<double> centroids;
  std::vector<float> values;
  for (double nm = 380; nm <= 760; nm += 5) {
    centroids.push_back(nm);
    values.push_back(static_cast<float>(0.1 + 0.001 * (nm - 380)));
  }
  const std::vector<double> centres = {420.5, 500, 563.2, 640, 700};
  const Sensor capture = Sensor::gaussian(centres, {12.0}, "test");
  const BandResampling r = BandResampling::through(centroids, capture, "test");
  std::vector<float> out(centres.size());
  r.apply(values.data(), out.data());
  for (size_t i = 0; i < centres.size(); ++i)
    EXPECT_NEAR(out[i], 0.1 + 0.001 * (centres[i] - 380), 1e-5) << centres[i];
  // Each row of weights sums to 1 (a flat spectrum stays flat).
  for (int i = 0; i < r.outputs(); ++i) {
    double sum = 0;
    for (int j = 0; j < r.inputs(); ++j)
      sum += r.weights()[static_cast<size_t>(i * r.inputs() + j)];
    EXPECT_NEAR(sum, 1.0, 1e-9);
  }
}

// Measured responses (--srf): symmetric triangles also average a linear spectrum to its value
// at their centre.
TEST(BandResampling, MeasuredTriangleResponsesGiveCentreValues) {
  const Sensor capture = Sensor::fromCsv(
      "nm,a,b\n460,0,0\n470,0,0\n480,1,0\n490,0,0\n600,0,0\n620,0,1\n640,0,0\n650,0,0\n",
      "srf.csv");
  std::vector<double> centroids;
  std::vector<float> values;
  for (double nm = 400; nm <= 700; nm += 5) {
    centroids.push_back(nm);
    values.push_back(static_cast<float>(2.0 - 0.002 * (nm - 400)));
  }
  const BandResampling r = BandResampling::through(centroids, capture, "srf.csv");
  float out[2];
  r.apply(values.data(), out);
  EXPECT_NEAR(out[0], 2.0 - 0.002 * 80, 1e-4);
  EXPECT_NEAR(out[1], 2.0 - 0.002 * 220, 1e-4);
}

TEST(BandResampling, BandsBeyondTheRenderAreRefused) {
  const Sensor capture = Sensor::gaussian({450, 690}, {20.0}, "test");
  EXPECT_THROW(BandResampling::through({400, 450, 500, 550, 600, 650, 700}, capture, "c.hdr"),
               Error);
  try {
    BandResampling::through({400, 450, 500, 550, 600, 650, 700}, capture, "c.hdr");
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("c.hdr: capture band 2 (centroid 690 nm, fwhm 20 nm) lies "
                                         "beyond the render's bands (400-700 nm)"),
              std::string::npos)
        << e.what();
  }
}

} // namespace
} // namespace nx

namespace nx {
namespace {

// Flat spectra have closed-form colours: reflectance rho under any illuminant has
// L* = 116 rho^(1/3) - 16 and a* = b* = 0; radiances under an equal-energy white scaled to the
// brightest region likewise.
TEST(CubeComparison, RegionColoursOfFlatSpectra) {
  auto lstar = [](double y) { return 116 * std::cbrt(y) - 16; };
  // CIEDE2000 of a pure lightness difference: dL / S_L.
  auto de = [](double l1, double l2) {
    const double m = (l1 + l2) / 2 - 50;
    return std::abs(l1 - l2) / (1 + 0.015 * m * m / std::sqrt(20 + m * m));
  };
  ComparisonReport rep;
  RegionFigures r;
  r.name = "card";
  r.pixels = 1;
  r.renderMean.assign(41, 0.18);
  r.captureMean.assign(41, 0.2);
  rep.regions.push_back(r);
  std::vector<double> nm;
  for (int i = 0; i <= 40; ++i) nm.push_back(380 + 10 * i);
  ColourOptions o;
  o.reflectance = true;
  o.illuminant = Spectrum(ConstantSpectrum{1.0});
  addRegionColours(rep, nm, o);
  EXPECT_NEAR(rep.regions[0].renderLab.l, lstar(0.18), 1e-6);
  EXPECT_NEAR(rep.regions[0].captureLab.l, lstar(0.2), 1e-6);
  EXPECT_NEAR(rep.regions[0].captureLab.a, 0, 1e-6);
  EXPECT_NEAR(rep.regions[0].deltaE2000, de(lstar(0.18), lstar(0.2)), 1e-6);
  // Radiances 1 and 0.5: the brighter is the white (L* = 100).
  rep.regions[0].renderMean.assign(41, 1.0);
  rep.regions[0].captureMean.assign(41, 0.5);
  o.reflectance = false;
  addRegionColours(rep, nm, o);
  EXPECT_NEAR(rep.regions[0].renderLab.l, 100, 1e-6);
  EXPECT_NEAR(rep.regions[0].captureLab.l, lstar(0.5), 1e-6);
  EXPECT_NEAR(rep.regions[0].deltaE2000, de(100, lstar(0.5)), 1e-6);
}

// Two noisy renders of one scene, compared with a fitted scale: the plain least-squares fit is
// low by the render's relative variance (E[r^2] = mu^2 + var r), the corrected fit is 1 within
// its error; with both sides' variances the band z-scores are N(0, 1) and the pooled rms z is
// 1. Closed forms: mu, the noise's variances and the sample size are known here.
TEST(CubeComparison, ScaleFitAndZScoresAccountForTheNoiseOfBothSides) {
  const int w = 100, h = 100, nb = 40;
  const size_t n = static_cast<size_t>(w * h * nb);
  std::mt19937 rng(17);
  std::normal_distribution<double> unit(0, 1);
  std::vector<float> render(n), capture(n), vr(n), vc(n);
  for (size_t i = 0; i < n; ++i) {
    const double mu = 1.0 + 0.5 * static_cast<double>(i % 7);
    // A 16-spp render (relative sd 0.3) against a 64-spp one (0.15); the renders' own
    // variance estimates, as a render stores them, scatter around the true ones.
    const double sr = 0.3 * mu, sc = 0.15 * mu;
    render[i] = static_cast<float>(mu + sr * unit(rng));
    capture[i] = static_cast<float>(mu + sc * unit(rng));
    vr[i] = static_cast<float>(sr * sr * (1 + 0.2 * unit(rng)));
    vc[i] = static_cast<float>(sc * sc * (1 + 0.2 * unit(rng)));
    if (i % 997 == 0) vr[i] = 0; // a pixel whose estimate is 0 (no lane in the band)
  }
  ComparisonInputs in;
  in.width = w, in.height = h, in.bands = nb;
  for (int b = 0; b < nb; ++b) in.wavelengthNm.push_back(400 + 10 * b);
  in.render = render.data();
  in.capture = capture.data();
  // Without variances: the plain fit, biased low by about 1 / (1 + 0.09).
  const ComparisonReport plain = compareCubes(in, ScaleFit::PerBand);
  double plainMean = 0;
  for (const BandFigures& f : plain.bands) plainMean += f.scale / nb;
  EXPECT_NEAR(plainMean, 1 / 1.09, 0.01);
  in.renderVariance = vr.data();
  in.captureVariance = vc.data();
  const ComparisonReport r = compareCubes(in, ScaleFit::PerBand);
  double z2 = 0, zMax = 0;
  for (const BandFigures& f : r.bands) {
    EXPECT_NEAR(f.scale, 1.0, 0.02) << f.wavelengthNm;
    EXPECT_NEAR(f.rmsZ, 1.0, 0.05) << f.wavelengthNm;
    z2 += f.zMean * f.zMean / nb;
    zMax = std::max(zMax, std::abs(f.zMean));
  }
  // With the scale fitted per band the bias is fitted away too: |z| is below N(0,1)'s, never
  // above it (the plain fit gave z of -50 and worse on two renders of the lab bench).
  EXPECT_LT(z2, 2.0);
  EXPECT_LT(zMax, 4.0);
  // No fit: z ~ N(0, 1) band by band, rms z 1.
  const ComparisonReport none = compareCubes(in, ScaleFit::None);
  double zn2 = 0;
  for (const BandFigures& f : none.bands) {
    zn2 += f.zMean * f.zMean / nb;
    EXPECT_NEAR(f.rmsZ, 1.0, 0.05);
  }
  EXPECT_GT(zn2, 0.4);
  EXPECT_LT(zn2, 1.9); // chi-square with 40 dof / 40: within [0.5, 1.6] at 99.9%
}

// Faint, heavy-tailed bands as a path tracer makes them (a pixel is the mean of a few samples,
// most 0, a few large; its variance estimate comes from the same samples): a scale fitted per
// band is then uncertain and correlated with the means, and the z-scores must hold that
// (two renders of the lab bench read z = 15 at 420 nm before). 16-sample renders against
// 64-sample ones of the same image: z ~ N(0, 1) over 40 bands.
TEST(CubeComparison, ZScoresHoldTheFittedScalesUncertainty) {
  const int w = 60, h = 60, nb = 40;
  const size_t np = static_cast<size_t>(w * h);
  std::mt19937 rng(23);
  std::uniform_real_distribution<double> u01(0, 1);
  std::vector<float> render(np * nb), capture(np * nb), vr(np * nb), vc(np * nb);
  auto pixel = [&](double mu, int samples, float& mean, float& var) {
    // A sample is 20 mu with probability 0.05, else 0 (mean mu, variance 19 mu^2).
    double s = 0, s2 = 0;
    for (int k = 0; k < samples; ++k) {
      const double x = u01(rng) < 0.05 ? 20 * mu : 0.0;
      s += x, s2 += x * x;
    }
    const double m = s / samples;
    mean = static_cast<float>(m);
    var = static_cast<float>((s2 / samples - m * m) / (samples - 1));
  };
  for (size_t p = 0; p < np; ++p)
    for (int b = 0; b < nb; ++b) {
      const double mu = 0.2 + 2.0 * static_cast<double>((p * 7 + b) % 13) / 13;
      const size_t i = p * nb + static_cast<size_t>(b);
      pixel(mu, 16, render[i], vr[i]);
      pixel(mu, 64, capture[i], vc[i]);
    }
  ComparisonInputs in;
  in.width = w, in.height = h, in.bands = nb;
  for (int b = 0; b < nb; ++b) in.wavelengthNm.push_back(400 + 10 * b);
  in.render = render.data();
  in.capture = capture.data();
  in.renderVariance = vr.data();
  in.captureVariance = vc.data();
  for (ScaleFit fit : {ScaleFit::PerBand, ScaleFit::None}) {
    const ComparisonReport r = compareCubes(in, fit);
    double z2 = 0, zMax = 0;
    for (const BandFigures& f : r.bands) {
      z2 += f.zMean * f.zMean / nb;
      zMax = std::max(zMax, std::abs(f.zMean));
    }
    EXPECT_GT(z2, 0.4) << static_cast<int>(fit);
    EXPECT_LT(z2, 1.9) << static_cast<int>(fit);
    EXPECT_LT(zMax, 4.0) << static_cast<int>(fit);
  }
}

} // namespace
} // namespace nx
